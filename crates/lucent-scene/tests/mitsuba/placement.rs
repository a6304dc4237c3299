//! Transforms in document order, and the camera they place: `lookat`, roll and `fov_axis`.

use super::support::*;
use glam::{Mat4, Vec3};

#[test]
fn transforms_compose_in_document_order() {
    let dir = Dir::new("transforms");
    let text = scene(
        r#"    <shape type="rectangle">
        <transform name="to_world">
            <scale x="2" y="3" z="1"/>
            <rotate y="1" angle="90"/>
            <translate x="1" y="2" z="3"/>
        </transform>
    </shape>
    <shape type="cube">
        <transform name="to_world">
            <matrix value="0 0 1 5
                           0 1 0 6
                          -1 0 0 7
                           0 0 0 1"/>
        </transform>
    </shape>
    <shape type="disk">
        <transform name="to_world">
            <rotate value="0, 0, 1" angle="90"/>
            <scale value="0.5"/>
        </transform>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <lookat origin="1, 2, 3" target="2, 2, 3" up="0, 1, 0"/>
        </transform>
    </shape>"#,
    );
    let path = dir.write("transforms.xml", &text);
    let imported = import(&path);
    let o = objects(&imported);

    // Scale, then 90° about +y, then translate: M = T · R · S. By hand, +x is scaled to
    // (2, 0, 0), turned to (0, 0, −2) and moved to (1, 2, 1); +y goes to (0, 3, 0) → (1, 5, 3).
    let m = transform(o[0]);
    let expected = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
        * Mat4::from_rotation_y(90f32.to_radians())
        * Mat4::from_scale(Vec3::new(2.0, 3.0, 1.0));
    assert!(m.abs_diff_eq(expected, 1e-6), "{m}");
    assert!(near(m.transform_point3(Vec3::X), Vec3::new(1.0, 2.0, 1.0)));
    assert!(near(m.transform_point3(Vec3::Y), Vec3::new(1.0, 5.0, 3.0)));

    // A matrix is written row by row: x' = z + 5, y' = y + 6, z' = −x + 7.
    let m = transform(o[1]);
    assert!(near(
        m.transform_point3(Vec3::new(1.0, 0.0, 0.0)),
        Vec3::new(5.0, 6.0, 6.0)
    ));
    assert!(near(
        m.transform_point3(Vec3::new(0.0, 0.0, 1.0)),
        Vec3::new(6.0, 6.0, 7.0)
    ));

    // An axis given as `value`; the rotation first, then the scale (a scale after a rotation
    // is still applied in world space).
    let m = transform(o[2]);
    assert!(near(m.transform_vector3(Vec3::X), Vec3::new(0.0, 0.5, 0.0)));
    assert!(near(
        m.transform_vector3(Vec3::Y),
        Vec3::new(-0.5, 0.0, 0.0)
    ));

    // Mitsuba's look_at: +z towards the target, +x = up × dir, +y = dir × (+x).
    let m = transform(o[3]);
    assert!(near(
        m.transform_point3(Vec3::ZERO),
        Vec3::new(1.0, 2.0, 3.0)
    ));
    assert!(near(m.transform_vector3(Vec3::Z), Vec3::X));
    assert!(near(m.transform_vector3(Vec3::X), -Vec3::Z));
    assert!(near(m.transform_vector3(Vec3::Y), Vec3::Y));

    // The built rectangle faces where the transform turns it: +z → +x.
    let (_, loaded) = load(&path);
    let world = loaded.scene.world_triangles();
    assert!(world.iter().any(|t| {
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
        near(n, Vec3::X) && near(t[0].min(t[1]).min(t[2]).x * Vec3::X, Vec3::X)
    }));
}

#[test]
fn a_lookat_places_and_rolls_the_camera() {
    let dir = Dir::new("camera");
    let text = scene(
        r#"    <sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world">
            <lookat origin="1, 2, 3" target="1, 2, 2" up="1, 1, 0"/>
        </transform>
        <film type="hdrfilm">
            <integer name="width" value="32"/>
            <integer name="height" value="32"/>
        </film>
    </sensor>
    <shape type="sphere"/>"#,
    );
    let path = dir.write("camera.xml", &text);
    let imported = import(&path);
    let cam = imported.desc.camera.get_ref();
    assert!(imported.camera_given);
    assert!(near(cam.eye.0.as_vec3(), Vec3::new(1.0, 2.0, 3.0)));
    assert!(near(
        (cam.look_at.0 - cam.eye.0).normalize().as_vec3(),
        -Vec3::Z
    ));
    // up' = dir × (up × dir): the given up made perpendicular to the view.
    let s = std::f32::consts::FRAC_1_SQRT_2;
    assert!(
        near(cam.up.0.normalize(), Vec3::new(s, s, 0.0)),
        "{:?}",
        cam.up
    );

    // Mitsuba's image has camera +x on its left, so its right is −(up × dir) = (1, −1, 0)/√2:
    // the built camera's right edge lies that way.
    let (_, loaded) = load(&path);
    let c = &loaded.scene.camera;
    let centre = c.ray(16.0, 16.0).dir;
    let right = c.ray(32.0, 16.0).dir - centre;
    assert!(right.dot(Vec3::new(s, -s, 0.0)) > 0.1, "{right}");
    assert!(right.dot(Vec3::new(s, s, 0.0)).abs() < 1e-5, "{right}");
}

#[test]
fn fov_axis_gives_the_right_vertical_fov() {
    let dir = Dir::new("fov");
    let half = |deg: f32| (deg.to_radians() / 2.0).tan();
    let full = |tan_half: f32| 2.0 * tan_half.atan().to_degrees();
    // (width, height, fov_axis, vertical fov) for a fov of 40°.
    let cases = [
        (200, 100, "x", full(half(40.0) / 2.0)),
        (200, 100, "y", 40.0),
        (200, 100, "smaller", 40.0),
        (200, 100, "larger", full(half(40.0) / 2.0)),
        (100, 200, "smaller", full(half(40.0) * 2.0)),
        (100, 200, "larger", 40.0),
        // tan(d/2)² = tan(x/2)² + tan(y/2)² with tan(x/2) = 2·tan(y/2).
        (200, 100, "diagonal", full(half(40.0) / 5f32.sqrt())),
    ];
    for (width, height, axis, vertical) in cases {
        let text = scene(&format!(
            r#"    <sensor type="perspective">
        <float name="fov" value="40"/>
        <string name="fov_axis" value="{axis}"/>
        <film type="hdrfilm">
            <integer name="width" value="{width}"/>
            <integer name="height" value="{height}"/>
        </film>
    </sensor>
    <shape type="sphere"/>"#
        ));
        let path = dir.write("fov.xml", &text);
        let (file, loaded) = load(&path);
        let fov = file.desc.camera.get_ref().fov.0;
        assert!(
            (fov - vertical).abs() < 1e-3,
            "{axis} {width}×{height}: {fov}"
        );
        // The built camera's angle along the named axis is Mitsuba's 40°, measured from the
        // centre ray to the middle of an edge (or to a corner for the diagonal).
        let c = &loaded.scene.camera;
        let (w, h) = (width as f32, height as f32);
        let centre = c.ray(w / 2.0, h / 2.0).dir;
        let wide = width > height;
        let edge = match (axis, wide) {
            ("x", _) | ("larger", true) | ("smaller", false) => c.ray(w, h / 2.0).dir,
            ("y", _) | ("smaller", true) | ("larger", false) => c.ray(w / 2.0, 0.0).dir,
            _ => c.ray(w, 0.0).dir,
        };
        let measured = 2.0 * angle(centre, edge);
        assert!(
            (measured - 40.0).abs() < 1e-2,
            "{axis} {width}×{height}: {measured}"
        );
    }
}

#[test]
fn a_sensors_shutter_is_the_cameras() {
    let dir = Dir::new("shutter");
    let sensor = |times: &str| {
        scene(&format!(
            "    <sensor type=\"perspective\">\n        {times}\n    </sensor>\n    <shape type=\"sphere\"/>"
        ))
    };
    let path = dir.write(
        "open.xml",
        sensor(
            r#"<float name="shutter_open" value="0.5"/><float name="shutter_close" value="1.25"/>"#,
        ),
    );
    let (file, loaded) = load(&path);
    let shutter = file.desc.camera.get_ref().shutter.as_ref().unwrap();
    assert_eq!(shutter.get_ref().map(|t| t.0), [0.5, 1.25]);
    let s = loaded.scene.shutter().unwrap();
    assert_eq!((s.open(), s.close()), (0.5, 1.25));
    // Mitsuba's default, closed at once, is no shutter.
    let path = dir.write("none.xml", sensor(""));
    assert!(load(&path).0.desc.camera.get_ref().shutter.is_none());
    // Closing before opening is Mitsuba's error too.
    let text =
        sensor(r#"<float name="shutter_open" value="2"/><float name="shutter_close" value="1"/>"#);
    let path = dir.write("backwards.xml", &text);
    let e = import_error(&path, &open());
    assert!(e.to_string().contains("before it opens"), "{e}");
}
