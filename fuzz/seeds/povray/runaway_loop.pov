#version 3.7;
global_settings { assumed_gamma 1.0 }
#declare R = 2 * (1 + 0.5);
#macro Ball(P, S) sphere { P, S pigment { rgb <10 ,.5, 0> } } #end
#local I = 0;
#while (I < 3) object { Ball(<I, 0, 0>, R / 4) } #declare I = I + 0; #end
#for (J, 0, 2) #if (mod(J, 1) = 0) box { <J, 1, 0>, <J +5 .0, 1.5, 0.5> } #else cylinder { <J, 1, 0>, <J, 2, 0>, 0.2 } #end #end
#switch (3) #case (1) torus { 1, 0.2 } #break #range (2, 4) cone { 0, 1, y, 0 } #break: #end
camera { location <0, 2, -6> look_at 0 angle 40 }
light_source { <4, 6, -5> color rgb 1 }
