//! The language and the scene read from small files.

use super::parser::Parser;
use super::scene::{PovScene, Shape};
use crate::paths::LoadOptions;
use std::path::Path;

fn read(text: &str) -> (PovScene, Parser) {
    let mut p = Parser::of_text(Path::new("t.pov"), text, &LoadOptions::default()).unwrap();
    let s = p.scene().unwrap_or_else(|e| panic!("{e}"));
    (s, p)
}

fn error(text: &str) -> String {
    let mut p = match Parser::of_text(Path::new("t.pov"), text, &LoadOptions::default()) {
        Ok(p) => p,
        Err(e) => return e.to_string(),
    };
    p.scene().expect_err("should be refused").to_string()
}

fn spheres(s: &PovScene) -> Vec<(f64, f64, f64, f64)> {
    s.objects
        .iter()
        .filter_map(|o| match o.shape {
            Shape::Sphere(c, r) => Some((c.x, c.y, c.z, r)),
            _ => None,
        })
        .collect()
}

#[test]
fn declares_expressions_and_loops() {
    let (s, _) = read(
        "#declare R = 2 * (1 + 0.5);\n#declare V = <1, 2, 3> + 1;\n#local I = 0;\n#while (I < 3)\n sphere { V * I, R + I }\n #declare I = I + 1;\n#end\n",
    );
    assert_eq!(
        spheres(&s),
        [
            (0.0, 0.0, 0.0, 3.0),
            (2.0, 3.0, 4.0, 4.0),
            (4.0, 6.0, 8.0, 5.0)
        ]
    );
}

#[test]
fn conditionals_switch_and_for() {
    let (s, _) = read(
        "#for (K, 1, 5, 2)\n #if (K = 3) sphere { 0, K } #elseif (K > 3) sphere { 1, K } #else sphere { 2, K } #end\n#end\n#switch (2)\n #case (1) sphere {3, 1} #break\n #range (2, 4) sphere {4, 1} #break\n #else sphere {5, 1}\n#end\n#ifdef (Nothing) sphere {6, 1} #end\n#ifndef (Nothing) sphere {7, 1} #end",
    );
    let r: Vec<(f64, f64)> = spheres(&s).iter().map(|s| (s.0, s.3)).collect();
    assert_eq!(
        r,
        [(2.0, 1.0), (0.0, 3.0), (1.0, 5.0), (4.0, 1.0), (7.0, 1.0)]
    );
}

#[test]
fn macros_take_arguments_and_keep_locals_local() {
    let (s, p) = read(
        "#macro Ball(C, R)\n #local Twice = R * 2;\n sphere { C, Twice }\n#end\n#macro Half(X) (X / 2) #end\nBall(<1, 0, 0>, Half(3))\n#declare Seen = defined(Twice);",
    );
    assert_eq!(spheres(&s), [(1.0, 0.0, 0.0, 3.0)]);
    assert!(matches!(
        p.lookup("Seen"),
        Some(super::value::Value::Float(0.0))
    ));
}

#[test]
fn arrays_functions_and_strings() {
    let (s, p) = read(
        "#declare A = array[3] {1, 4, 9};\n#declare A[1] = sqrt(A[2]) + max(1, 2, 7);\nsphere { <A[1], vlength(<3, 4, 0>), dimension_size(A, 1)>, 1 }\n#declare S = concat(\"a\", str(1.5, 0, 1));\n#declare B = (S = \"a1.5\") & !false;",
    );
    assert_eq!(spheres(&s), [(10.0, 5.0, 3.0, 1.0)]);
    assert!(matches!(
        p.lookup("B"),
        Some(super::value::Value::Float(1.0))
    ));
}

#[test]
fn objects_declared_and_placed() {
    let (s, _) = read(
        "#declare Ball = sphere { 0, 1 pigment { color rgb <1, 0, 0> } }\nobject { Ball translate <0, 2, 0> }\nunion { object { Ball } box { -1, 1 } scale 2 }",
    );
    assert_eq!(s.objects.len(), 2);
    let placed = s.objects[0].transform.transform_point3(glam::DVec3::ZERO);
    assert_eq!(placed, glam::DVec3::new(0.0, 2.0, 0.0));
    assert!(matches!(&s.objects[1].shape, Shape::Csg(_, c) if c.len() == 2));
}

#[test]
fn errors_name_the_place_and_what_was_expected() {
    let e = error("sphere { <0, 0, 0>, 1\n  pigment { colour rgb <1, 0, 0> }\n  bogus 3 }");
    assert!(
        e.starts_with("t.pov:3:3: `bogus` is not an object modifier"),
        "{e}"
    );
    let e = error("#declare X = 1;\nsphere { <0, 0, 0>, }");
    assert!(
        e.starts_with("t.pov:2:21: expected a value, found `}`"),
        "{e}"
    );
    let e = error("sphere { <0, 0, 0>, 1");
    assert!(e.contains("the file ends where `}` was expected"), "{e}");
    let e = error("#if (1)\nsphere { 0, 1 }\n");
    assert!(e.contains("never closed by `#end`"), "{e}");
    let e = error("sphere { 0, Radius }");
    assert!(e.starts_with("t.pov:1:13: `Radius` is not declared"), "{e}");
    let e = error("#include \"nowhere.inc\"");
    assert!(
        e.starts_with("t.pov:1:1: the include file \"nowhere.inc\""),
        "{e}"
    );
    let e = error("#macro M(A) M(A) #end\nM(1)");
    assert!(e.contains("nest more than"), "{e}");
    let e = error("#while (1) #end");
    assert!(e.contains("turned more than"), "{e}");
}

#[test]
fn a_macro_assigns_an_identifier_passed_to_it() {
    let (s, p) = read(
        "#macro Grow(Stuff, By)\n #declare Stuff = Stuff + By;\n#end\n#declare R = 1;\nGrow(R, 2)\nsphere { 0, R }",
    );
    assert!(
        matches!(p.lookup("R"), Some(super::value::Value::Float(3.0))),
        "{:?}",
        p.lookup("R")
    );
    assert_eq!(spheres(&s), [(0.0, 0.0, 0.0, 3.0)]);
}

#[test]
fn a_macro_turns_an_object_passed_to_it() {
    let (s, _) = read(
        "#macro Turn_Me(Stuff,Degrees,Axis)\n    #declare Stuff=object{Stuff rotate Axis*Degrees}\n#end\n#declare Thing = sphere{x, 1}\nTurn_Me(Thing,90,z)\nobject{Thing}",
    );
    let p = s.objects[0].transform.transform_point3(glam::DVec3::X);
    assert!((p - glam::DVec3::Y).length() < 1e-9, "{p}");
}
