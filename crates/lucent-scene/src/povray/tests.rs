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
    // Runaways end in about a second: a loop that never stops, one that makes objects, and a
    // macro that calls itself twice at each of 100 levels (2¹⁰⁰ calls, never too deep).
    let started = std::time::Instant::now();
    let e = error("#while (1) #end");
    assert!(e.contains("run more than"), "{e}");
    let e = error("#declare I = 0;\n#while (I < 10) sphere { I, 1 } #end");
    assert!(e.contains("more than 100000 objects"), "{e}");
    let e = error("#macro M(N) #if (N > 0) M(N - 1) M(N - 1) #end #end\nM(100)");
    assert!(e.contains("run more than"), "{e}");
    // Timed loosely (debug builds, a shared machine): the point is that they end.
    assert!(started.elapsed().as_secs() < 60);
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

fn algebraic(
    s: &PovScene,
) -> (
    lucent::shape::solid::algebraic::Coefficients,
    Option<[glam::DVec3; 2]>,
) {
    match &s.objects[0].shape {
        Shape::Algebraic(c) => (**c, s.objects[0].bounds),
        other => panic!("not algebraic: {other:?}"),
    }
}

#[test]
fn quadrics_and_quartics_read_in_povrays_order() {
    use glam::DVec3;
    use lucent::shape::solid::algebraic::value;
    // x² + 2y² + 3z² + 4xy + 5xz + 6yz + 7x + 8y + 9z + 10.
    let (s, _) = read("quadric { <1, 2, 3>, <4, 5, 6>, <7, 8, 9>, 10 }");
    let (c, bounds) = algebraic(&s);
    let p = DVec3::new(0.5, -1.0, 2.0);
    let want = 0.25 + 2.0 + 12.0 - 2.0 + 5.0 - 12.0 + 3.5 - 8.0 + 18.0 + 10.0;
    assert!((value(&c, p) - want).abs() < 1e-12, "{}", value(&c, p));
    assert_eq!(bounds, None);
    // The piriform, commas left out between rows as the sample scenes write it, bounded by a
    // sphere and then scaled: the box stays in the shape's own space.
    let (s, _) = read(
        "quartic { <4, 0, 0, -4, 0, 0, 0, 0, 0, 0\n 0, 0, 0, 0, 0, 0, 0, 0, 0, 0\n 0, 0, 0, 0, 0, 1, 0, 0, 0, 0\n 0, 0, 1, 0, 0> bounded_by { sphere { 0, 2 } } scale 3 }",
    );
    let (c, bounds) = algebraic(&s);
    let p = DVec3::new(0.5, 0.2, 0.1);
    assert!((value(&c, p) - (0.25 - 0.5 + 0.04 + 0.01)).abs() < 1e-12);
    assert_eq!(bounds, Some([DVec3::splat(-2.0), DVec3::splat(2.0)]));
    // Clipped by two planes: bounded along z only.
    let (s, _) =
        read("quadric { <1, 1, 0>, 0, 0, -1 clipped_by { plane { z, 2 } plane { -z, 1 } } }");
    let [lo, hi] = algebraic(&s).1.unwrap();
    assert_eq!((lo.z, hi.z), (-1.0, 2.0));
    assert!(lo.x.is_infinite() && hi.y.is_infinite());
}

#[test]
fn polynomials_lucent_cannot_read_are_named() {
    let text = format!("poly {{ 5, <{}> }}", vec!["1"; 56].join(", "));
    let (s, _) = read(&text);
    assert!(matches!(&s.objects[0].shape, Shape::Unread(w) if w.contains("degree `5")));
    let imported = super::import_povray_text(Path::new("t.pov"), &text, &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        imported.warnings[0].contains("t.pov:1:1: the shape `poly` of degree `5` is not read"),
        "{:?}",
        imported.warnings
    );
    let e = error("quartic { <1, 2, 3> }");
    assert!(
        e.contains("t.pov:1:1") && e.contains("35 coefficients, not 3"),
        "{e}"
    );
    let e = error("quadric { <0, 0, 0>, 0, 0, 1 }");
    assert!(e.contains("no term with x, y or z"), "{e}");
}

#[test]
fn a_plane_in_a_combination_is_a_half_space_and_a_lone_quadric_is_cut() {
    use crate::desc::ObjectKind;
    let text = "intersection { sphere { 0, 1 } plane { y, 0.25 } pigment { rgb 1 } }\nquadric { <1, 1, 0>, 0, 0, -1 pigment { rgb 1 } }";
    let imported = super::import_povray_text(Path::new("t.pov"), text, &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let objects = &imported.desc.objects;
    let cut = objects[0].get_ref().children.as_ref().unwrap();
    let half = cut.get_ref()[1].get_ref();
    assert_eq!(half.kind, ObjectKind::Algebraic);
    assert_eq!(
        half.terms.as_ref().unwrap().get_ref(),
        &vec![[1.0, 0.0, 1.0, 0.0], [-0.25, 0.0, 0.0, 0.0]]
    );
    let lone = objects[1].get_ref();
    assert_eq!(lone.kind, ObjectKind::Algebraic);
    assert!(lone.bounds.is_some());
    assert!(
        imported
            .warnings
            .iter()
            .any(|w| w.contains("t.pov:2:1") && w.contains("cut to the box"))
    );
}

#[test]
fn normals_are_read_with_their_depth_and_placement() {
    let text = "#declare N = normal { ripples 0.8 frequency 2 }\nsphere { 0, 1 normal { bumps 0.4 scale 0.2 } }\nsphere { 0, 1 normal { N bump_size 0.3 } translate x }\nsphere { 0, 1 normal { checker normal { bumps } normal { dents } } }";
    let (s, p) = read(text);
    let normal = |i: usize| {
        s.objects[i]
            .texture
            .as_ref()
            .unwrap()
            .normal
            .clone()
            .unwrap()
    };
    assert_eq!(normal(0).amount, 0.4);
    assert!((normal(0).pattern.transform.matrix3.x_axis.x - 0.2).abs() < 1e-12);
    // A declared normal, its depth changed, moved with its object.
    let n = normal(1);
    assert_eq!((n.amount, n.pattern.shaping.frequency), (0.3, Some(2.0)));
    assert_eq!(n.pattern.transform.translation.x, 1.0);
    // A pattern of normals: read whole, not applied.
    assert!(!normal(2).unread.is_empty());
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    let imported = super::import_povray_text(Path::new("t.pov"), text, &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let bumps = imported
        .desc
        .materials
        .iter()
        .filter(|m| m.get_ref().bump.is_some())
        .count();
    assert_eq!(bumps, 2, "the bumps and the ripples");
    assert!(
        imported
            .warnings
            .iter()
            .any(|w| w.contains("t.pov:4") && w.contains("`checker`")),
        "{:?}",
        imported.warnings
    );
}
