//! Debug views (`--integrator debug:NAME`) show what their names say.

mod common;

use common::render_scene;

/// Two spheres, the near one in the middle of the image and a farther one to the right, with
/// a floor of triangles below: enough for every view to have something to show.
const SCENE: &str = r#"
[image]
width = 41
height = 31
[camera]
eye = [0, 0, 6]
look_at = [0, 0, 0]
fov = 40
[[material]]
name = "red"
kd = [0.8, 0.1, 0.1]
[[material]]
name = "grey"
kd = 0.5
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "red"
[[object]]
type = "sphere"
center = [2.2, 0, -4]
radius = 1
material = "grey"
[[object]]
type = "triangle"
vertices = [[-4, -1.5, 2], [4, -1.5, 2], [0, -1.5, -8]]
material = "grey"
"#;

fn view(name: &str, extra: &[&str]) -> common::Image {
    let mut args = vec!["--integrator", name];
    args.extend(extra);
    render_scene(SCENE, &args)
}

#[test]
fn normals_of_a_sphere_seen_head_on_point_at_the_camera() {
    let img = view("debug:normals", &[]);
    // The centre pixel sees the sphere's point nearest the eye: normal (0, 0, 1).
    let [r, g, b] = img.center();
    let n = glam::Vec3::new(2.0 * r - 1.0, 2.0 * g - 1.0, 2.0 * b - 1.0);
    assert!(n.dot(glam::Vec3::Z) > 0.999, "{n}");
    // Right of centre the normal leans right, above it up (rows count from the top).
    let right = img.at(23, 15);
    let up = img.at(20, 13);
    assert!(right[0] > 0.5 && (up[1] > 0.5), "{right:?} {up:?}");
    assert_eq!(img.at(0, 0), [0.0; 3], "a miss is black");
}

#[test]
fn depth_grows_with_distance() {
    let img = view("debug:depth", &[]);
    let near = img.center()[0];
    // The far sphere's middle: (2.2, 0, -4) is 10 units away, the near sphere's front 5.
    let far = img.at(28, 15)[0];
    assert!(near < far && far < 1.0, "{near} {far}");
    // The floor recedes: lower rows (nearer) are darker than rows nearer the horizon.
    assert!(img.at(20, 30)[0] < img.at(20, 24)[0]);
    assert_eq!(img.at(0, 0)[0], 1.0, "a miss is white");
}

#[test]
fn the_brute_force_heat_map_is_uniform_and_the_bvhs_is_not() {
    let brute = view("debug:cost", &["--accel", "brute"]);
    let first = brute.pixels[0];
    assert!(
        brute.pixels.iter().all(|&p| p == first),
        "every ray tests every object"
    );
    assert!(first != [0.0; 3]);
    let bvh = view("debug:cost", &["--accel", "bvh"]);
    let distinct: std::collections::HashSet<[u32; 3]> =
        bvh.pixels.iter().map(|p| p.map(f32::to_bits)).collect();
    assert!(distinct.len() > 2, "{}", distinct.len());
}

#[test]
fn ids_are_stable_and_tell_objects_apart() {
    let a = view("debug:id", &[]);
    let b = view("debug:id", &["--accel", "octree", "--threads", "1"]);
    assert_eq!(a, b);
    let (near, far, floor) = (a.center(), a.at(28, 15), a.at(20, 30));
    assert!(near != far && far != floor && near != floor);
    assert_eq!(a.at(0, 0), [0.0; 3]);
}

#[test]
fn albedo_and_barycentrics() {
    let albedo = view("debug:albedo", &[]);
    assert_eq!(albedo.center(), [0.8, 0.1, 0.1]);
    let bary = view("debug:barycentrics", &[]);
    // On the floor triangle the weights sum to 1; on the spheres they are 0.
    let [a, b, c] = bary.at(20, 30);
    assert!((a + b + c - 1.0).abs() < 1e-4 && a > 0.0 && b > 0.0 && c > 0.0);
    assert_eq!(bary.center(), [0.0; 3]);
}
