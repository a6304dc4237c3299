//! Shapes, BSDFs and emitters as lucent's objects, materials and lights, and the warnings for what it renders otherwise.

use super::support::*;
use glam::Vec3;
use lucent::Rgb;
use lucent::integrator::RayStats;
use lucent_scene::desc::texture::Encoding;
use lucent_scene::desc::{
    ImageMapDesc, LightDesc, LightKind, MaterialKind, ObjectKind, TextureDesc,
};

#[test]
fn shapes_map_onto_objects() {
    let dir = Dir::new("shapes");
    dir.write("meshes/quad.obj", QUAD_OBJ);
    dir.write("tri.ply", TRIANGLE_PLY);
    let text = scene(
        r#"    <shape type="obj">
        <string name="filename" value="meshes/quad.obj"/>
        <boolean name="face_normals" value="true"/>
        <transform name="to_world"><translate z="-2"/></transform>
    </shape>
    <shape type="ply">
        <string name="filename" value="tri.ply"/>
        <boolean name="flip_normals" value="true"/>
    </shape>
    <shape type="sphere">
        <point name="center" x="1" y="2" z="3"/>
        <float name="radius" value="0.5"/>
        <transform name="to_world"><scale value="2"/><translate x="1"/></transform>
    </shape>
    <shape type="rectangle"/>
    <shape type="cube"/>
    <shape type="disk">
        <boolean name="flip_normals" value="true"/>
    </shape>"#,
    );
    let path = dir.write("shapes.xml", &text);
    let imported = import(&path);
    assert!(imported.warnings.is_empty(), "{:#?}", imported.warnings);
    let o = objects(&imported);
    let kinds: Vec<ObjectKind> = o.iter().map(|o| o.kind).collect();
    use ObjectKind::*;
    assert_eq!(kinds, [Mesh, Mesh, Sphere, Rectangle, Cube, Disk]);
    assert_eq!(o[0].file.as_ref().unwrap().get_ref(), "meshes/quad.obj");
    assert_eq!(o[0].smooth, Some(false), "face_normals");
    assert!(near(
        transform(o[0]).transform_point3(Vec3::ZERO),
        -2.0 * Vec3::Z
    ));
    assert_eq!(o[1].file.as_ref().unwrap().get_ref(), "tri.ply");
    assert_eq!((o[1].smooth, o[1].flip_normals), (None, Some(true)));
    assert!(o[1].transform.is_none());
    // to_world · translate(center) · scale(radius): centre 2·(1, 2, 3) + (1, 0, 0), radius 1.
    assert_eq!(
        o[2].center.as_ref().unwrap().get_ref().0.as_vec3(),
        Vec3::new(3.0, 4.0, 6.0)
    );
    assert_eq!(o[2].radius.as_ref().unwrap().get_ref().0, 1.0);
    assert!(o[3].transform.is_none() && o[4].transform.is_none());
    assert_eq!(o[5].flip_normals, Some(true));
    // Mitsuba's default BSDF: one diffuse grey for them all.
    let m = material(&imported, o[0].material.get_ref());
    assert_eq!(m.kind(), MaterialKind::Diffuse);
    assert_eq!(m.reflectance, Some(TextureDesc::Solid(Rgb::gray(0.5))));
    assert!(o.iter().all(|x| x.material == o[0].material));

    let (_, loaded) = load(&path);
    let c = loaded.scene.counts();
    assert_eq!((c.spheres, c.instances), (1, 5));
    assert_eq!(
        c.triangles,
        2 + 1 + 2 + 12 + lucent_scene::build::shapes::DISK_SEGMENTS as usize
    );
}

#[test]
fn flip_normals_turns_a_disk_around() {
    let dir = Dir::new("flip");
    let mut facing = Vec::new();
    for flip in [false, true] {
        let text = scene(&format!(
            r#"    <shape type="disk"><boolean name="flip_normals" value="{flip}"/></shape>"#
        ));
        let path = dir.write("disk.xml", &text);
        let (_, loaded) = load(&path);
        let ray = lucent::accel::Ray::new(Vec3::new(0.1, 0.1, 5.0), -Vec3::Z);
        let hit = loaded
            .scene
            .intersect(&ray, &mut RayStats::default().traversal)
            .unwrap();
        facing.push(hit.normal);
    }
    assert!(near(facing[0], Vec3::Z), "{facing:?}");
    assert!(near(facing[1], -Vec3::Z), "{facing:?}");
}

#[test]
fn spheres_lucent_cannot_draw_are_refused_or_warned_about() {
    let dir = Dir::new("sphere-limits");
    // Scaled unevenly: the exact ellipsoid, hit where its radii put it.
    let text = scene(
        r#"    <shape type="sphere">
        <float name="radius" value="0.5"/>
        <transform name="to_world"><scale x="1" y="2" z="3"/><translate x="1"/></transform>
    </shape>"#,
    );
    let path = dir.write("ellipsoid.xml", &text);
    let (file, loaded) = load(&path);
    assert_eq!(loaded.scene.counts().solids, 1);
    let (line, column) = position(&text, "<transform");
    let said = format!("ellipsoid.xml:{line}:{column}: this sphere's to_world scales unevenly");
    assert!(
        file.warnings.iter().any(|w| w.contains(&said)),
        "{:?}",
        file.warnings
    );
    let mut stats = RayStats::default().traversal;
    let down = lucent::accel::Ray::new(Vec3::new(1.0, 5.0, 0.0), -Vec3::Y);
    let along = lucent::accel::Ray::new(Vec3::new(1.0, 0.0, 5.0), -Vec3::Z);
    let mut t = |r| loaded.scene.intersect(&r, &mut stats).map(|h| h.t);
    assert!(
        (t(down).unwrap() - 4.0).abs() < 1e-5,
        "radius 0.5 · 2 along y"
    );
    assert!(
        (t(along).unwrap() - 3.5).abs() < 1e-5,
        "radius 0.5 · 3 along z"
    );

    let text = scene(r#"    <shape type="sphere"><float name="radius" value="1e-12"/></shape>"#);
    let path = dir.write("tiny.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        position(&text, "<shape"),
        "outside lucent's range",
    );

    // Mitsuba turns an inward-facing sphere inside out; lucent's spheres face out, and says so
    // rather than failing the build.
    let text =
        scene(r#"    <shape type="sphere"><boolean name="flip_normals" value="true"/></shape>"#);
    let path = dir.write("flipped.xml", &text);
    let (file, _) = load(&path);
    assert_eq!(file.desc.objects[0].get_ref().flip_normals, None);
    let (line, column) = position(&text, "<shape");
    let said = format!("flipped.xml:{line}:{column}: `flip_normals` of a sphere is not read");
    assert!(
        file.warnings.iter().any(|w| w.contains(&said)),
        "{:?}",
        file.warnings
    );
}

#[test]
fn bsdfs_map_onto_material_kinds() {
    let dir = Dir::new("bsdfs");
    image::RgbImage::from_pixel(2, 2, image::Rgb([255, 0, 0]))
        .save(dir.path("red.png"))
        .unwrap();
    let shape = |bsdf: &str| format!("    <shape type=\"cube\">\n        {bsdf}\n    </shape>\n");
    let bsdfs = [
        r#"<bsdf type="diffuse" id="rgb"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf>"#,
        r#"<bsdf type="diffuse" id="bitmap"><texture type="bitmap" name="reflectance"><string name="filename" value="red.png"/></texture></bsdf>"#,
        r#"<bsdf type="conductor" id="gold"><string name="material" value="Au"/></bsdf>"#,
        r#"<bsdf type="conductor" id="mirror"/>"#,
        r#"<bsdf type="roughconductor" id="brushed"><float name="alpha" value="0.2"/><string name="distribution" value="ggx"/><rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3.9, 2.4, 2.1"/></bsdf>"#,
        r#"<bsdf type="dielectric" id="water"><string name="int_ior" value="water"/><float name="ext_ior" value="1"/></bsdf>"#,
        r#"<bsdf type="roughdielectric" id="frosted"><float name="alpha" value="0.3"/><string name="distribution" value="ggx"/></bsdf>"#,
        r#"<bsdf type="plastic" id="plastic"><rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/><float name="int_ior" value="1.6"/></bsdf>"#,
        r#"<bsdf type="roughplastic" id="satin"><string name="distribution" value="ggx"/><float name="alpha" value="0.05"/></bsdf>"#,
        r#"<bsdf type="twosided" id="paper"><bsdf type="diffuse"><rgb name="reflectance" value="0.9"/></bsdf></bsdf>"#,
        r#"<bsdf type="twosided" id="card"><bsdf type="diffuse"/><bsdf type="conductor" id="card-back"/></bsdf>"#,
        r#"<bsdf type="roughconductor" id="satin-metal"><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/></bsdf>"#,
        r#"<bsdf type="roughplastic" id="glossy"><boolean name="nonlinear" value="true"/></bsdf>"#,
        r#"<bsdf type="thindielectric" id="pane"/>"#,
        r#"<bsdf type="blendbsdf" id="mix"><float name="weight" value="0.25"/><ref id="rgb"/><ref id="gold"/></bsdf>"#,
        r#"<bsdf type="mask" id="leaf"><float name="opacity" value="0.3"/><ref id="rgb"/></bsdf>"#,
        r#"<bsdf type="bumpmap" id="bumpy"><texture type="bitmap"><string name="filename" value="red.png"/><boolean name="raw" value="true"/></texture><float name="scale" value="2"/><ref id="plastic"/></bsdf>"#,
        r#"<bsdf type="normalmap" id="dented"><texture type="bitmap" name="normalmap"><string name="filename" value="red.png"/><boolean name="raw" value="true"/></texture><ref id="rgb"/></bsdf>"#,
    ];
    let text = scene(&bsdfs.map(shape).concat());
    let path = dir.write("bsdfs.xml", &text);
    let imported = import(&path);
    assert!(imported.warnings.is_empty(), "{:#?}", imported.warnings);
    let m = |name: &str| material(&imported, name);
    let solid = |t: &TextureDesc| match t {
        TextureDesc::Solid(c) => *c,
        other => panic!("a constant, got {other:?}"),
    };
    let roughness = |name: &str| m(name).roughness.as_ref().map(|r| solid(r.get_ref()).r);
    let ior = |name: &str| m(name).ior.as_ref().map(|r| r.get_ref().0);
    let ext_ior = |name: &str| m(name).ext_ior.as_ref().map(|r| r.get_ref().0);

    assert_eq!(m("rgb").kind(), MaterialKind::Diffuse);
    assert_eq!(
        m("rgb").reflectance,
        Some(TextureDesc::Solid(Rgb::new(0.2, 0.4, 0.6)))
    );
    assert_eq!(
        m("rgb").two_sided,
        Some(false),
        "Mitsuba's BSDFs are one-sided"
    );
    let mut red = ImageMapDesc::new("red.png");
    red.encoding = Some(Encoding::Srgb);
    assert_eq!(
        m("bitmap").reflectance,
        Some(TextureDesc::Image(red.clone()))
    );
    assert_eq!(m("gold").kind(), MaterialKind::Conductor);
    assert_eq!(m("gold").metal.as_ref().unwrap().get_ref(), "Au");
    // Mitsuba's default conductor, "none", reflects everything: η = 0, k = 1.
    assert_eq!(solid(m("mirror").eta.as_ref().unwrap()), Rgb::BLACK);
    assert_eq!(solid(m("mirror").k.as_ref().unwrap()), Rgb::WHITE);
    assert_eq!(m("brushed").kind(), MaterialKind::RoughConductor);
    assert_eq!(roughness("brushed"), Some(0.2));
    assert_eq!(m("brushed").distribution.as_ref().unwrap().get_ref(), "ggx");
    assert_eq!(
        solid(m("brushed").eta.as_ref().unwrap()),
        Rgb::new(0.2, 0.9, 1.1)
    );
    assert_eq!(m("water").kind(), MaterialKind::Dielectric);
    assert_eq!((ior("water"), ext_ior("water")), (Some(1.333), Some(1.0)));
    assert_eq!(
        m("water").two_sided,
        None,
        "a dielectric has two sides by nature"
    );
    assert_eq!(m("frosted").kind(), MaterialKind::RoughDielectric);
    assert_eq!(roughness("frosted"), Some(0.3));
    // Mitsuba's defaults: BK7 inside, air outside.
    assert_eq!(
        (ior("frosted"), ext_ior("frosted")),
        (Some(1.5046), Some(1.000277))
    );
    assert_eq!(m("plastic").kind(), MaterialKind::Plastic);
    assert_eq!(
        m("plastic").reflectance,
        Some(TextureDesc::Solid(Rgb::new(0.1, 0.2, 0.3)))
    );
    assert_eq!((ior("plastic"), roughness("plastic")), (Some(1.6), None));
    assert_eq!(m("satin").kind(), MaterialKind::RoughPlastic);
    assert_eq!((ior("satin"), roughness("satin")), (Some(1.49), Some(0.05)));
    assert_eq!(m("paper").kind(), MaterialKind::Diffuse);
    assert_eq!(m("paper").two_sided, Some(true));
    // Two BSDFs: the front's, with the back's material behind it.
    assert_eq!(m("card").kind(), MaterialKind::Diffuse);
    assert_eq!(m("card").back.as_ref().unwrap().get_ref(), "card-back");
    // Mitsuba's default microfacets: Beckmann; anisotropic roughness kept as it is.
    let sm = m("satin-metal");
    assert_eq!(sm.distribution.as_ref().unwrap().get_ref(), "beckmann");
    assert_eq!(solid(sm.roughness_u.as_ref().unwrap().get_ref()).r, 0.05);
    assert_eq!(solid(sm.roughness_v.as_ref().unwrap().get_ref()).r, 0.4);
    assert_eq!(m("glossy").nonlinear, Some(true));
    assert_eq!(roughness("glossy"), Some(0.1));
    assert_eq!(m("pane").kind(), MaterialKind::ThinDielectric);
    assert_eq!(m("mix").kind(), MaterialKind::Blend);
    assert_eq!(
        m("mix").materials.as_ref().unwrap().get_ref(),
        &vec!["rgb".to_string(), "gold".to_string()]
    );
    assert_eq!(solid(m("mix").weight.as_ref().unwrap().get_ref()).r, 0.25);
    assert_eq!(m("leaf").kind(), MaterialKind::Diffuse);
    assert_eq!(solid(m("leaf").opacity.as_ref().unwrap().get_ref()).r, 0.3);
    let mut raw = red.clone();
    raw.encoding = Some(Encoding::Linear);
    assert_eq!(m("bumpy").kind(), MaterialKind::Plastic);
    assert_eq!(
        m("bumpy").bump_map.as_ref().unwrap().get_ref(),
        &TextureDesc::Image(raw.clone())
    );
    assert_eq!(m("bumpy").bump_scale.as_ref().unwrap().get_ref().0, 2.0);
    assert_eq!(
        m("dented").normal_map.as_ref().unwrap().get_ref(),
        &TextureDesc::Image(raw)
    );

    // The build takes them all, the texture read from its file.
    let (_, loaded) = load(&path);
    assert_eq!(
        loaded.scene.images.len(),
        2,
        "red.png decoded as sRGB and as raw data"
    );
    let water = loaded
        .scene
        .materials
        .iter()
        .filter(|m| (m.ior - 1.333).abs() < 1e-6)
        .count();
    assert_eq!(water, 1);
}

#[test]
fn emitters_map_onto_lights() {
    let dir = Dir::new("emitters");
    let text = scene(
        r#"    <emitter type="point">
        <point name="position" x="1" y="4" z="2"/>
        <rgb name="intensity" value="5, 6, 7"/>
    </emitter>
    <emitter type="spot">
        <transform name="to_world"><lookat origin="0, 5, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
        <float name="intensity" value="30"/>
    </emitter>
    <emitter type="directional">
        <vector name="direction" x="0" y="-1" z="-1"/>
        <rgb name="irradiance" value="2"/>
    </emitter>
    <emitter type="constant">
        <rgb name="radiance" value="0.1, 0.2, 0.3"/>
    </emitter>
    <shape type="sphere">
        <emitter type="area"><rgb name="radiance" value="4"/></emitter>
    </shape>"#,
    );
    let path = dir.write("emitters.xml", &text);
    let imported = import(&path);
    let v = |l: &LightDesc| l.position.as_ref().unwrap().get_ref().0.as_vec3();
    let d = |l: &LightDesc| l.direction.as_ref().unwrap().get_ref().0;
    let point = light(&imported, LightKind::Point);
    assert_eq!(v(point), Vec3::new(1.0, 4.0, 2.0));
    assert_eq!(point.intensity.unwrap().0, Rgb::new(5.0, 6.0, 7.0));
    let spot = light(&imported, LightKind::Spot);
    assert!(near(v(spot), Vec3::new(0.0, 5.0, 0.0)));
    assert!(near(d(spot).normalize(), -Vec3::Y));
    // Mitsuba's defaults: cutoff 20°, the beam ¾ of it.
    assert_eq!(spot.cutoff.as_ref().unwrap().get_ref().0, 20.0);
    assert_eq!(spot.cutoff_start.as_ref().unwrap().get_ref().0, 15.0);
    let sun = light(&imported, LightKind::Directional);
    assert_eq!(d(sun), Vec3::new(0.0, -1.0, -1.0));
    assert_eq!(sun.intensity.unwrap().0, Rgb::gray(2.0));
    let sky = light(&imported, LightKind::Environment);
    assert_eq!(sky.intensity.unwrap().0, Rgb::new(0.1, 0.2, 0.3));
    assert_eq!(imported.desc.lights.len(), 4);
    let glow = material(&imported, objects(&imported)[0].material.get_ref());
    assert_eq!(glow.emission, Some(TextureDesc::Solid(Rgb::gray(4.0))));
    let (_, loaded) = load(&path);
    // Rendered by the path tracer, as Mitsuba renders a scene without an <integrator>: the
    // area light is an emitting surface, sampled as such, not one of the scene's lights.
    assert_eq!(
        loaded.scene.lights.len(),
        3,
        "the point, spot and directional lights"
    );
    assert_eq!(loaded.scene.background, Rgb::new(0.1, 0.2, 0.3));

    // An environment map, scaled.
    image::Rgb32FImage::from_pixel(4, 2, image::Rgb([1.0, 0.5, 0.25]))
        .save(dir.path("sky.exr"))
        .unwrap();
    let text = scene(
        r#"    <emitter type="envmap">
        <string name="filename" value="sky.exr"/>
        <float name="scale" value="2"/>
    </emitter>"#,
    );
    let path = dir.write("envmap.xml", &text);
    let imported = import(&path);
    let sky = light(&imported, LightKind::Environment);
    assert_eq!(sky.file.as_ref().unwrap().get_ref(), "sky.exr");
    assert_eq!(sky.intensity.unwrap().0, Rgb::gray(2.0));
    // Mitsuba's image centre faces +z, lucent's −z: without a to_world, a half turn about +y.
    let r = sky
        .rotation
        .as_ref()
        .expect("a rotation")
        .get_ref()
        .0
        .as_mat4();
    assert!(
        r.x_axis
            .abs_diff_eq(glam::Vec4::new(-1.0, 0.0, 0.0, 0.0), 1e-6),
        "{r}"
    );
    assert!(
        r.z_axis
            .abs_diff_eq(glam::Vec4::new(0.0, 0.0, -1.0, 0.0), 1e-6),
        "{r}"
    );
    assert!(
        !imported.warnings.iter().any(|w| w.contains("to_world")),
        "{:?}",
        imported.warnings
    );
    let (_, loaded) = load(&path);
    assert!(loaded.scene.environment.is_some());

    // Mitsuba takes one environment emitter, and so does lucent.
    let text = scene(
        r#"    <emitter type="constant"/>
    <emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>"#,
    );
    let path = dir.write("two-skies.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        position(&text, r#"<emitter type="envmap""#),
        "a second environment emitter",
    );
}

#[test]
fn approximations_warn_once_per_kind() {
    let dir = Dir::new("approximations");
    let text = scene(
        r#"    <integrator type="path"/>
    <shape type="rectangle"><emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>
    <shape type="disk"><emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>
    <shape type="cube"><bsdf type="roughconductor"/></shape>
    <shape type="cube"><bsdf type="roughdielectric"/></shape>
    <shape type="cube"><bsdf type="roughplastic" id="shared"/></shape>
    <shape type="cube"><ref id="shared"/></shape>
    <shape type="cube"><bsdf type="twosided"><ref id="shared"/></bsdf></shape>
    <shape type="cube"><bsdf type="roughconductor"><string name="distribution" value="ggx"/></bsdf></shape>"#,
    );
    let path = dir.write("approx.xml", &text);
    let (_, loaded) = load(&path);
    let w = &loaded.warnings;
    // The path tracer renders the area lights and rough materials (Beckmann and GGX) as
    // they are.
    assert!(w.is_empty(), "{w:#?}");

    // Under Whitted, the area lights become point lights and the rough materials Phong
    // highlights, each said once.
    let mut file = lucent_scene::SceneFile::read_with(&path, &open()).unwrap();
    file.desc.render.integrator = lucent_scene::desc::IntegratorName::Whitted;
    let w = file.build().unwrap().warnings;
    let count = |words: &str| w.iter().filter(|l| l.contains(words)).count();
    assert_eq!(count("2 area lights become"), 1, "{w:#?}");
    assert_eq!(count("rough materials"), 1, "{w:#?}");
}

#[test]
fn a_plugin_read_twice_warns_once() {
    let dir = Dir::new("read-twice");
    image::RgbImage::from_pixel(1, 1, image::Rgb([9, 9, 9]))
        .save(dir.path("grey.png"))
        .unwrap();
    let text = scene(
        r#"    <texture type="bitmap" id="grain">
        <string name="filename" value="grey.png"/>
        <string name="format" value="variant"/>
    </texture>
    <bsdf type="diffuse" id="wood"><ref name="reflectance" id="grain"/></bsdf>
    <bsdf type="diffuse" id="oak"><ref name="reflectance" id="grain"/><float name="sheen" value="1"/></bsdf>
    <shape type="cube"><ref id="wood"/></shape>
    <shape type="cube"><ref id="oak"/></shape>
    <shape type="cube"><bsdf type="twosided"><ref id="oak"/></bsdf></shape>"#,
    );
    let path = dir.write("twice.xml", &text);
    let imported = import(&path);
    let w = &imported.warnings;
    assert_eq!(
        w.iter()
            .filter(|l| l.contains("`format` of the bitmap texture is not read"))
            .count(),
        1,
        "{w:#?}"
    );
    let (line, column) = position(&text, r#"<float name="sheen""#);
    let sheen =
        format!("twice.xml:{line}:{column}: `sheen` of the diffuse bsdf is not read by lucent");
    assert_eq!(w.iter().filter(|l| l.contains(&sheen)).count(), 1, "{w:#?}");
    assert_eq!(w.len(), 2, "{w:#?}");
}
