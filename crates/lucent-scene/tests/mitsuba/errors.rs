//! Refusals: one line naming the file, line and column of the fault.

use super::support::*;
use lucent_scene::SceneFile;

#[test]
fn an_unknown_plugin_type_is_refused() {
    let dir = Dir::new("unknown-type");
    let text = scene(
        r#"    <shape type="sphere">
        <bsdf type="hair"/>
    </shape>"#,
    );
    let path = dir.write("hair.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        position(&text, "<bsdf"),
        "unknown bsdf type `hair`",
    );
    assert!(
        e.message.contains("diffuse"),
        "it lists what lucent reads: {e}"
    );
}

#[test]
fn a_missing_mesh_file_is_refused_at_its_name() {
    let dir = Dir::new("missing-mesh");
    let text = scene(
        r#"    <shape type="obj">
        <string name="filename" value="meshes/gone.obj"/>
    </shape>"#,
    );
    let path = dir.write("gone.xml", &text);
    let e = import_error(&path, &open());
    assert_error(&e, &path, after(&text, r#"filename" value=""#), "mesh file");
    assert!(
        e.message.contains("gone.obj") && e.message.contains("not found"),
        "{e}"
    );
    let e = SceneFile::read_with(&path, &open()).unwrap_err();
    assert_eq!(e.position, Some(after(&text, r#"filename" value=""#)));
}

#[test]
fn malformed_xml_is_refused_where_the_parser_stops() {
    let dir = Dir::new("malformed");
    let text = scene(
        r#"    <shape type="sphere">
        <float name="radius" value="1"/>"#,
    );
    let path = dir.write("unclosed.xml", &text);
    let e = import_error(&path, &open());
    assert_error(&e, &path, position(&text, "</scene>"), "malformed XML");
    assert!(e.message.contains("shape"), "{e}");
}

#[test]
fn the_sandbox_refuses_files_outside_the_scene_folder() {
    let dir = Dir::new("sandbox");
    let outside = dir.write("elsewhere/quad.obj", QUAD_OBJ);
    dir.write("elsewhere/walls.xml", scene(r#"    <shape type="cube"/>"#));
    let absolute = outside.to_str().unwrap().to_string();
    let cases = [
        (
            "dotdot.xml",
            "../elsewhere/quad.obj",
            "leaves the scene's folder",
        ),
        ("absolute.xml", absolute.as_str(), "absolute path"),
    ];
    for (name, file, words) in cases {
        let text = scene(&format!(
            r#"    <shape type="obj">
        <string name="filename" value="{file}"/>
    </shape>"#
        ));
        let path = dir.write(&format!("scenes/{name}"), &text);
        let e = import_error(&path, &sandboxed());
        assert_error(&e, &path, after(&text, r#"filename" value=""#), words);
        // Without the sandbox the file is read and built.
        let imported = import_with(&path, &open()).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            imported.desc.objects[0]
                .get_ref()
                .file
                .as_ref()
                .unwrap()
                .get_ref(),
            file
        );
        let (_, loaded) = load(&path);
        assert_eq!(loaded.scene.counts().triangles, 2);
    }
    // Includes too.
    let text = scene(r#"    <include filename="../elsewhere/walls.xml"/>"#);
    let path = dir.write("scenes/include.xml", &text);
    let e = import_error(&path, &sandboxed());
    assert_error(
        &e,
        &path,
        after(&text, r#"filename=""#),
        "leaves the scene's folder",
    );
    assert_eq!(import(&path).desc.objects.len(), 1);
    // A name that goes out and comes back stays inside.
    dir.write("scenes/in/quad.obj", QUAD_OBJ);
    let text = scene(
        r#"    <shape type="obj"><string name="filename" value="in/../in/quad.obj"/></shape>"#,
    );
    let path = dir.write("scenes/inside.xml", &text);
    import_with(&path, &sandboxed()).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_non_numeric_float_is_refused_at_its_value() {
    let dir = Dir::new("nan");
    let text = scene(
        r#"    <sensor type="perspective">
        <float name="fov" value="wide"/>
    </sensor>"#,
    );
    let path = dir.write("fov.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        after(&text, r#"fov" value=""#),
        "cannot read `wide` as a number",
    );
}
