//! Images with known answers, rendered through the command line to linear PFM.

mod common;

use common::{assert_close, render_scene};

/// A diffuse sphere (kd 0.5) lit by a point light at the eye: the centre pixel sees the point
/// facing the light head-on (N·L = 1), so it shows kd·I.
#[test]
fn diffuse_sphere_lit_from_the_eye_shows_kd_times_i() {
    let scene = r#"
        [image]
        width = 33
        height = 33
        [camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        fov = 30
        [[material]]
        name = "matte"
        kd = 0.5
        [[light]]
        type = "point"
        position = [0, 0, 5]
        intensity = [1.0, 0.8, 0.6]
        [[object]]
        type = "sphere"
        center = [0, 0, 0]
        radius = 1
        material = "matte"
    "#;
    let img = render_scene(scene, &[]);
    assert_close(img.center(), [0.5, 0.4, 0.3], 0.01);
    // Off centre, N·L falls and so does the colour; outside the sphere, the black background.
    assert!(img.at(20, 16)[0] < 0.5 && img.at(20, 16)[0] > 0.0);
    assert_eq!(img.at(0, 0), [0.0; 3]);
    // With quadratic falloff the light at distance 4 delivers I/16.
    let quadratic = scene.replace(
        "intensity = [1.0, 0.8, 0.6]",
        "intensity = [16.0, 12.8, 9.6]\nfalloff = \"quadratic\"",
    );
    assert_close(
        render_scene(&quadratic, &[]).center(),
        [0.5, 0.4, 0.3],
        0.01,
    );
}

/// A point on the floor in the shadow of a sphere, with the light straight above it, gets only
/// the ambient term ka·Ia.
#[test]
fn a_point_in_shadow_gets_ambient_only() {
    let scene = r#"
        [image]
        width = 21
        height = 21
        [camera]
        eye = [0, 0.3, 3]
        look_at = [0, 0, 0]
        fov = 20
        [world]
        ambient = [0.2, 0.3, 0.4]
        [[material]]
        name = "floor"
        ka = 0.5
        kd = 0.8
        ks = 0.5
        shininess = 10
        [[material]]
        name = "ball"
        kd = 0.7
        [[light]]
        type = "point"
        position = [0, 5, 0]
        intensity = 1
        [[object]]
        type = "plane"
        point = [0, 0, 0]
        normal = [0, 1, 0]
        material = "floor"
        [[object]]
        type = "sphere"
        center = [0, 1, 0]
        radius = 0.5
        material = "ball"
    "#;
    let img = render_scene(scene, &[]);
    assert_close(img.center(), [0.1, 0.15, 0.2], 1e-4);
    // Without the ball, the same point is lit: ka·Ia + kd·I·(N·L = 1) + ks·(R·V)^10.
    // The view and light lie in one plane through the normal, so R·V = cos(angle between them).
    let lit = render_scene(
        &scene.replace("center = [0, 1, 0]", "center = [5, 1, -5]"),
        &[],
    );
    let v = glam::Vec3::new(0.0, 0.3, 3.0).normalize();
    let specular = 0.5 * v.y.powi(10); // R = L = +y mirrored about +y
    let want = |ia: f32| 0.5 * ia + 0.8 + specular;
    assert_close(lit.center(), [want(0.2), want(0.3), want(0.4)], 1e-4);
    // Without shadow rays the ball casts no shadow: the point is lit as if it were not there.
    let unshadowed = render_scene(scene, &["--no-shadows"]);
    assert_close(unshadowed.center(), lit.center(), 1e-6);
}

/// A mirror of kr 0.5 shows half the colour of what it reflects.
#[test]
fn a_half_mirror_shows_half_the_reflected_colour() {
    let scene = r#"
        [image]
        width = 21
        height = 21
        [camera]
        eye = [0, 1, 5]
        look_at = [0, 0, 0]
        fov = 10
        [world]
        ambient = 1
        background = [0.1, 0.2, 0.9]
        [[material]]
        name = "mirror"
        kr = 0.5
        [[material]]
        name = "wall"
        ka = [0.8, 0.4, 0.2]
        [[object]]
        type = "plane"
        point = [0, 0, 0]
        normal = [0, 1, 0]
        material = "mirror"
        [[object]]
        type = "plane"
        point = [0, 0, -10]
        normal = [0, 0, 1]
        material = "wall"
    "#;
    let img = render_scene(scene, &[]);
    assert_close(img.center(), [0.4, 0.2, 0.1], 1e-5);
    // Looking at the wall directly (raised camera, level gaze) shows its full colour.
    let direct = render_scene(
        &scene
            .replace("eye = [0, 1, 5]", "eye = [0, 2, 5]")
            .replace("look_at = [0, 0, 0]", "look_at = [0, 2, -10]"),
        &[],
    );
    assert_close(direct.center(), [0.8, 0.4, 0.2], 1e-5);
    // With recursion off, the mirror shows nothing but its own (zero) local terms.
    assert_close(
        render_scene(scene, &["--max-depth", "0"]).center(),
        [0.0; 3],
        1e-6,
    );
}

/// Ray casting shows each surface's flat diffuse colour, unlit.
#[test]
fn raycast_shows_flat_diffuse_colour() {
    let scene = r#"
        [image]
        width = 9
        height = 9
        [camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        [world]
        background = [0, 0, 1]
        [[material]]
        name = "m"
        kd = [0.25, 0.5, 0.75]
        [[object]]
        type = "triangle"
        vertices = [[-1, -1, 0], [1, -1, 0], [0, 1, 0]]
        material = "m"
    "#;
    let img = render_scene(scene, &["--integrator", "raycast"]);
    assert_eq!(img.center(), [0.25, 0.5, 0.75]);
    assert_eq!(img.at(0, 0), [0.0, 0.0, 1.0]);
}

/// A glass ball seen head-on against a white background: the centre ray passes undeflected,
/// and the depth limit decides which bounces count.
#[test]
fn glass_transmits_kt_and_reflects_kr() {
    let scene = r#"
        [image]
        width = 11
        height = 11
        [camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        fov = 5
        [world]
        background = 1
        [[material]]
        name = "glass"
        kt = 0.8
        kr = 0.1
        ior = 1.5
        [[object]]
        type = "sphere"
        center = [0, 0, 0]
        radius = 1
        material = "glass"
    "#;
    // Depth 1: the front surface reflects kr of the background; the refracted ray reaches the
    // back surface at the depth limit, where only its (black) local terms count.
    assert_close(
        render_scene(scene, &["--max-depth", "1"]).center(),
        [0.1; 3],
        1e-5,
    );
    // Depth 2: the refracted ray also leaves through the back surface, kt of kt:
    // kr + kt·(kt·1 + kr·0) = 0.1 + 0.8·0.8 = 0.74.
    assert_close(
        render_scene(scene, &["--max-depth", "2"]).center(),
        [0.74; 3],
        1e-5,
    );
}
