//! What ties a scene's text together: `<default>`s and `$name`s, `<include>`s, `<ref>`s and ids.

use super::support::*;
use glam::Vec3;
use lucent::Rgb;
use lucent_scene::SceneFile;
use lucent_scene::desc::{ObjectKind, TextureDesc};

#[test]
fn defaults_fill_in_names_and_an_undefined_name_is_refused_at_its_value() {
    let dir = Dir::new("defaults");
    let text = scene(
        r#"    <default name="r" value="0.25"/>
    <default name="tint" value="0.1, 0.2, 0.3"/>
    <default name="r" value="9"/>
    <default name="rx" value="4"/>
    <shape type="sphere">
        <float name="radius" value="$r"/>
        <point name="center" x="$rx" y="-$r" z="1$rx"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="$tint"/></bsdf>
    </shape>"#,
    );
    let path = dir.write("defaults.xml", &text);
    let imported = import(&path);
    let o = objects(&imported)[0];
    // The first definition of `r` wins; `$rx` is `rx`, not `r` followed by "x"; a name may
    // stand inside a value.
    assert_eq!(o.radius.as_ref().unwrap().get_ref().0, 0.25);
    assert_eq!(
        o.center.as_ref().unwrap().get_ref().0.as_vec3(),
        Vec3::new(4.0, -0.25, 14.0)
    );
    assert_eq!(
        material(&imported, o.material.get_ref()).reflectance,
        Some(TextureDesc::Solid(Rgb::new(0.1, 0.2, 0.3)))
    );

    let text = scene(
        r#"    <default name="spp" value="4"/>
    <shape type="sphere">
        <float name="radius" value="$size"/>
    </shape>"#,
    );
    let path = dir.write("undefined.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        after(&text, r#"<float name="radius" value=""#),
        "`$size` is not defined",
    );
    // The usual route gives the same line.
    let e = SceneFile::read_with(&path, &open()).unwrap_err();
    assert_error(&e, &path, after(&text, r#"radius" value=""#), "`$size`");
}

#[test]
fn defaults_that_double_each_other_are_refused_before_they_fill_the_memory() {
    let dir = Dir::new("doubling");
    let mut body = String::from("    <default name=\"d0\" value=\"0123456789\"/>\n");
    for i in 1..=40 {
        body += &format!(
            "    <default name=\"d{i}\" value=\"$d{p}$d{p}\"/>\n",
            p = i - 1
        );
    }
    let path = dir.write("doubling.xml", scene(&body));
    let e = import_error(&path, &open());
    assert!(e.message.contains("expand to more than"), "{e}");
    assert!(e.position.is_some(), "{e}");
}

#[test]
fn an_include_adds_its_shapes_and_its_errors_name_it() {
    let dir = Dir::new("include");
    let main = scene(
        r#"    <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5"/></bsdf>
    <include filename="parts/spheres.xml"/>
    <shape type="cube"><ref id="grey"/></shape>"#,
    );
    // Included files are found from the main scene's folder, as Mitsuba's resolver does, even
    // from inside another include.
    dir.write(
        "parts/spheres.xml",
        scene(
            r#"    <shape type="sphere"><float name="radius" value="0.5"/><ref id="grey"/></shape>
    <include filename="parts/disk.xml"/>"#,
        ),
    );
    dir.write(
        "parts/disk.xml",
        r#"<shape type="disk"><transform name="to_world"><translate z="-3"/></transform></shape>"#,
    );
    let path = dir.write("main.xml", &main);
    let imported = import(&path);
    let kinds: Vec<ObjectKind> = objects(&imported).iter().map(|o| o.kind).collect();
    assert_eq!(
        kinds,
        [ObjectKind::Sphere, ObjectKind::Disk, ObjectKind::Cube]
    );
    let o = objects(&imported);
    assert_eq!(o[0].material.get_ref(), "grey", "a ref across files");
    assert!(near(
        transform(o[1]).transform_point3(Vec3::ZERO),
        Vec3::new(0.0, 0.0, -3.0)
    ));
    let (_, loaded) = load(&path);
    assert_eq!(loaded.scene.counts().spheres, 1);

    // An error inside the included file is placed there.
    let bad = scene(r#"    <shape type="sphere"><float name="radius" value="huge"/></shape>"#);
    let bad_path = dir.write("parts/bad.xml", &bad);
    let path = dir.write(
        "uses-bad.xml",
        scene(r#"    <include filename="parts/bad.xml"/>"#),
    );
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &bad_path,
        after(&bad, r#"radius" value=""#),
        "cannot read `huge` as a number",
    );

    // A missing include is refused at its file name.
    let text = scene(r#"    <include filename="parts/nowhere.xml"/>"#);
    let path = dir.write("missing-include.xml", &text);
    let e = import_error(&path, &open());
    assert_error(&e, &path, after(&text, r#"filename=""#), "nowhere.xml");
}

#[test]
fn an_include_cycle_is_refused_naming_the_files() {
    let dir = Dir::new("cycle");
    let a = scene(r#"    <include filename="b.xml"/>"#);
    let b = scene(
        r#"    <shape type="cube"/>
    <include filename="a.xml"/>"#,
    );
    let a_path = dir.write("a.xml", &a);
    let b_path = dir.write("b.xml", &b);
    let e = import_error(&a_path, &open());
    assert_error(&e, &b_path, position(&b, "<include"), "include cycle");
    let shown = e.to_string();
    let a_at = shown.rfind("a.xml`").unwrap();
    let b_at = shown.rfind("b.xml`").unwrap();
    assert!(b_at < a_at, "a → b → a: {shown}");

    // Including itself is the shortest cycle.
    let own = scene(r#"    <include filename="own.xml"/>"#);
    let own_path = dir.write("own.xml", &own);
    let e = import_error(&own_path, &open());
    assert_error(&e, &own_path, position(&own, "<include"), "include cycle");
    assert!(e.message.contains("own.xml"), "{e}");
}

#[test]
fn a_ref_shares_one_bsdf_and_an_unknown_one_is_refused() {
    let dir = Dir::new("ref");
    let text = scene(
        r#"    <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.8"/></bsdf>
    <bsdf type="twosided" id="both"><ref id="white"/></bsdf>
    <shape type="rectangle"><ref id="white"/></shape>
    <shape type="cube"><ref name="bsdf" id="white"/></shape>
    <shape type="disk"><ref id="both"/></shape>"#,
    );
    let path = dir.write("ref.xml", &text);
    let imported = import(&path);
    let names: Vec<&str> = objects(&imported)
        .iter()
        .map(|o| o.material.get_ref().as_str())
        .collect();
    assert_eq!(names, ["white", "white", "both"]);
    assert_eq!(imported.desc.materials.len(), 2);
    assert_eq!(material(&imported, "white").two_sided, Some(false));
    let both = material(&imported, "both");
    assert_eq!(both.two_sided, Some(true));
    assert_eq!(both.reflectance, Some(TextureDesc::Solid(Rgb::gray(0.8))));
    load(&path);

    let text = scene(r#"    <shape type="cube"><ref id="whit"/></shape>"#);
    let path = dir.write("unknown-ref.xml", &text);
    let e = import_error(&path, &open());
    assert_error(&e, &path, after(&text, r#"<ref id=""#), "unknown id `whit`");
}

#[test]
fn a_duplicate_id_is_refused_at_the_second() {
    let dir = Dir::new("duplicate-id");
    let text = scene(
        r#"    <bsdf type="diffuse" id="paint"/>
    <shape type="cube">
        <bsdf type="conductor" id="paint"/>
    </shape>"#,
    );
    let path = dir.write("dup.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        after(&text, r#"<bsdf type="conductor" id=""#),
        "the id `paint` is given twice",
    );
    let (line, column) = position(&text, r#"<bsdf type="diffuse""#);
    assert!(
        e.message
            .contains(&format!("(first at {}:{line}:{column})", path.display())),
        "{e}"
    );
}
