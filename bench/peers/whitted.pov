// examples/whitted.toml in POV-Ray 3.7's language, for timing the classic renderer against
// POV-Ray on the same scene (bench/peers/povray_whitted.sh). Terms mapped as docs/design.md's
// Whitted model reads them: kd -> diffuse with the pigment as its colour, ks/shininess -> phong/
// phong_size, kr -> reflection, kt -> the pigment's transmit with the interior's ior,
// ka·Ia -> ambient with ambient_light = Ia. lucent is right-handed and POV-Ray left-handed:
// `right -x` keeps the image unmirrored.
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 10
  adc_bailout 0.00390625
  ambient_light rgb 0.15
}

camera {
  perspective
  location <0.0, 1.3, 6.0>
  look_at <0.0, 0.9, 0.0>
  sky y
  right -x * image_width / image_height
  // lucent's fov = 38 is vertical; POV-Ray's angle is horizontal: 2·atan(tan(19°)·4/3).
  angle 49.32
}

background { color rgb <0.15, 0.35, 0.85> }

light_source { <-4.0, 7.0, 6.0> color rgb 0.75 }
light_source { <5.0, 6.0, 2.0> color rgb 0.45 }

plane {
  y, 0
  pigment { checker color rgb <0.85, 0.1, 0.05> color rgb <0.95, 0.8, 0.1> }
  finish { ambient 0.6 diffuse 1.0 phong 0.1 phong_size 20 }
}

sphere {
  <0.9, 1.2, -1.6>, 1.2
  pigment { color rgb 1 }
  finish { ambient 0.1 diffuse 0.05 phong 0.7 phong_size 120 reflection 0.8 }
}

sphere {
  <-0.7, 0.9, 1.0>, 0.75
  pigment { color rgbt <1, 1, 1, 0.88> }
  finish { ambient 0 diffuse 0 phong 0.7 phong_size 200 reflection 0.1 }
  interior { ior 1.5 }
}
