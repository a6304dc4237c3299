camera { orthographic location <0, 0, -5> look_at 0 right 4*x up 3*y }
light_source { <2, 4, -3> rgb 1 area_light x, y, 3, 3 }
background { rgb 0.1 }
intersection { sphere { 0, 1 } plane { y, 0.25 } texture { pigment { checker rgb 1 rgb 0 scale 0.2 } finish { phong 0.5 reflection 0.2 } } }
difference { box { -1, 1 } cylinder { -2*z, 2*z, 0.5 } translate 2*x interior { ior 1.5 } }
quartic { <4, 0, 0, -4, 0, 0, 0, 0, 0, 0 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 0, 0, 0, 0, 0, 1, 0, 0, 0, 0 0, 0, 1, 0, 0> bounded_by { sphere { 0, 2 } } pigment { rgb x } translate -2*x }
quadric { <1, 1, 0>, 0, 0, -1 clipped_by { plane { z, 1 } plane { -z, 1 } } }
superellipsoid { <0.3, 0.7> pigment { marble turbulence 0.5 color_map { [0 rgb 0] [1 rgb 1] } } translate y }
mesh2 { vertex_vectors { 3, <0,0,0>, <1,0,0>, <0,1,0> } face_indices { 1, <0,1,2> } }
polygon { 4, <0,0>, <1,0>, <1,1>, <0,1> pigment { wood } }
