//! `<medium>`, `<phase>`, the `null` BSDF and `volpath`: read as `[[medium]]` tables, objects'
//! `interior`/`exterior` and the camera's medium; what lucent cannot read refused at its place.

use super::support::*;
use lucent::Rgb;
use lucent_scene::desc::{IntegratorName, MaterialKind, MediumDesc};

fn medium<'a>(imported: &'a lucent_scene::Imported, name: &str) -> &'a MediumDesc {
    imported
        .desc
        .media
        .iter()
        .map(|m| m.get_ref())
        .find(|m| m.name.get_ref() == name)
        .unwrap_or_else(|| panic!("no medium `{name}`"))
}

fn color(c: &Option<lucent_scene::Spanned<lucent_scene::desc::Color>>) -> Option<Rgb> {
    c.as_ref().map(|c| c.get_ref().0)
}

#[test]
fn media_are_read_where_shapes_and_the_sensor_name_them() {
    let dir = Dir::new("media");
    let text = scene(
        r#"    <integrator type="volpath"><integer name="max_depth" value="10"/></integrator>
    <medium type="homogeneous" id="fog">
        <float name="sigma_t" value="0.5"/>
        <phase type="isotropic"/>
    </medium>
    <sensor type="perspective"><ref id="fog"/></sensor>
    <shape type="sphere">
        <bsdf type="null"/>
        <medium type="homogeneous" name="interior">
            <rgb name="sigma_t" value="0.2, 0.4, 1"/>
            <float name="scale" value="3"/>
            <rgb name="albedo" value="0.9, 0.5, 0.1"/>
            <phase type="hg"/>
        </medium>
        <ref name="exterior" id="fog"/>
    </shape>"#,
    );
    let path = dir.write("media.xml", &text);
    let imported = import(&path);
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    let d = &imported.desc;
    assert_eq!(d.render.integrator, IntegratorName::Path);
    assert_eq!(*d.render.max_depth.get_ref(), 8);
    assert_eq!(d.media.len(), 2, "the fog is read once, though named twice");
    assert_eq!(d.camera.get_ref().medium.as_ref().unwrap().get_ref(), "fog");
    let fog = medium(&imported, "fog");
    // Mitsuba's defaults: albedo 0.75, scale 1; an isotropic phase function.
    assert_eq!(color(&fog.sigma_t), Some(Rgb::gray(0.5)));
    assert_eq!(color(&fog.albedo), Some(Rgb::gray(0.75)));
    assert_eq!(fog.g.as_ref().map(|g| g.get_ref().0), Some(0.0));
    let o = objects(&imported)[0];
    assert_eq!(o.exterior.as_ref().unwrap().get_ref(), "fog");
    let inside = medium(&imported, o.interior.as_ref().unwrap().get_ref());
    assert_eq!(color(&inside.sigma_t), Some(Rgb::new(0.2, 0.4, 1.0)));
    assert_eq!(inside.scale.as_ref().map(|s| s.get_ref().0), Some(3.0));
    assert_eq!(color(&inside.albedo), Some(Rgb::new(0.9, 0.5, 0.1)));
    // Mitsuba's hg: g = 0.8 unless given.
    assert_eq!(inside.g.as_ref().map(|g| g.get_ref().0), Some(0.8));
    assert_eq!(
        material(&imported, o.material.get_ref()).kind(),
        MaterialKind::Null
    );
    // And it builds: the camera is in the fog, the sphere bounds a medium.
    let (_, loaded) = load(&path);
    assert!(loaded.scene.has_media());
    assert_eq!(loaded.scene.camera_medium(), Some(0));
}

#[test]
fn media_lucent_cannot_read_are_refused_at_their_place() {
    let dir = Dir::new("media-refused");
    let cases = [
        (
            r#"    <shape type="sphere"><medium type="spatiallyvarying" name="interior"/></shape>"#,
            "<medium",
            "unknown medium type `spatiallyvarying` (lucent reads: homogeneous, heterogeneous)",
        ),
        (
            r#"    <shape type="sphere"><medium type="homogeneous"/></shape>"#,
            "<medium",
            "named \"interior\" or \"exterior\"",
        ),
        (
            r#"    <shape type="sphere"><medium type="homogeneous" name="interior"><rgb name="albedo" value="0.5, 1.2, 0.5"/></medium></shape>"#,
            "<medium",
            "albedo must be at most 1",
        ),
        (
            r#"    <shape type="sphere"><medium type="homogeneous" name="interior"><phase type="hg"><float name="g" value="1"/></phase></medium></shape>"#,
            "<phase",
            "strictly between −1 and 1",
        ),
        (
            r#"    <shape type="sphere"><medium type="homogeneous" name="interior"><phase type="rayleigh"/></medium></shape>"#,
            "<phase",
            "unknown phase type `rayleigh`",
        ),
        (
            r#"    <shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="gridvolume" name="albedo"><string name="filename" value="g.vol"/></volume></medium></shape>"#,
            "<volume",
            "an albedo grid needs a `sigma_t` grid",
        ),
        (
            r#"    <shape type="sphere"><medium type="homogeneous" name="interior"><volume type="gridvolume" name="sigma_t"/></medium></shape>"#,
            "<volume",
            "a grid of `sigma_t` is not read",
        ),
        (
            r#"    <shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="gridvolume" name="sigma_t"><string name="filename" value="g.vol"/><transform name="to_world"><rotate y="1" angle="30"/></transform></volume></medium></shape>"#,
            "<transform",
            "without turning or mirroring it",
        ),
        (
            r#"    <shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="gridvolume" name="sigma_t"><string name="filename" value="g.vol"/><string name="filter_type" value="nearest"/></volume></medium></shape>"#,
            "nearest",
            "filter_type `nearest` is not read",
        ),
        (
            r#"    <shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="gridvolume" name="density"/></medium></shape>"#,
            "<volume",
            "a medium's volumes are `sigma_t` and `albedo`, not `density`",
        ),
        (
            r#"    <shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="gridvolume" name="sigma_t"><string name="filename" value="missing.vol"/></volume></medium></shape>"#,
            "missing.vol",
            "not found",
        ),
    ];
    dir.write("g.vol", lucent_scene::vol::write_vol(&grid()));
    for (i, (body, at, words)) in cases.into_iter().enumerate() {
        let text = scene(body);
        let path = dir.write(&format!("bad-{i}.xml"), &text);
        let e = import_error(&path, &open());
        assert_error(&e, &path, position(&text, at), words);
    }
}

fn grid() -> lucent_scene::vol::VolGrid {
    lucent_scene::vol::VolGrid {
        res: [2, 3, 4],
        channels: 1,
        values: (0..24).map(|i| i as f32 / 10.0).collect(),
        bounds: (glam::Vec3::ZERO, glam::Vec3::ONE),
    }
}

#[test]
fn a_heterogeneous_medium_reads_its_grid_and_where_it_lies() {
    let dir = Dir::new("media-grid");
    dir.write("smoke/grid.vol", lucent_scene::vol::write_vol(&grid()));
    let text = scene(
        r#"    <integrator type="volpath"/>
    <shape type="cube">
        <bsdf type="null"/>
        <medium type="heterogeneous" name="interior">
            <volume name="sigma_t" type="gridvolume">
                <string name="filename" value="smoke/grid.vol"/>
                <transform name="to_world"><scale x="2" y="4" z="6"/><translate x="-1" y="-2" z="-3"/></transform>
            </volume>
            <volume name="albedo" type="constvolume"><rgb name="value" value="0.9, 0.8, 0.7"/></volume>
            <float name="scale" value="20"/>
            <integer name="majorant_resolution_factor" value="8"/>
        </medium>
    </shape>"#,
    );
    let path = dir.write("grid.xml", &text);
    let imported = import(&path);
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    let o = objects(&imported)[0];
    let m = medium(&imported, o.interior.as_ref().unwrap().get_ref());
    assert_eq!(m.density.as_ref().unwrap().get_ref(), "smoke/grid.vol");
    let [lo, hi] = m.bounds.as_ref().unwrap().get_ref();
    assert_eq!(
        (lo.0, hi.0),
        (
            glam::DVec3::new(-1.0, -2.0, -3.0),
            glam::DVec3::new(1.0, 2.0, 3.0)
        )
    );
    assert_eq!(color(&m.sigma_t), Some(Rgb::WHITE));
    assert_eq!(color(&m.albedo), Some(Rgb::new(0.9, 0.8, 0.7)));
    assert_eq!(m.scale.as_ref().map(|s| s.get_ref().0), Some(20.0));
    let (_, loaded) = load(&path);
    let built = loaded.scene.medium(0);
    let density = built.density.as_ref().expect("a grid");
    assert_eq!(density.resolution(), [2, 3, 4]);
    // Voxel (1, 0, 3)'s centre is the unit cube's (3/4, 1/6, 7/8): the scene's (0.5, −4/3,
    // 2.25); nearer the face than the first centre in y, the value is held.
    let want = grid().values[1 + 2 * 3 * 3];
    for y in [-4.0 / 3.0, -1.8] {
        let got = density.density(glam::Vec3::new(0.5, y, 2.25));
        assert!((got - want).abs() < 1e-5, "at y {y}: {got} not {want}");
    }
}

#[test]
fn an_albedo_grid_is_read_over_the_density_grids_box_and_refused_elsewhere() {
    let dir = Dir::new("media-albedo-grid");
    dir.write("g.vol", lucent_scene::vol::write_vol(&grid()));
    let rgb = lucent_scene::vol::VolGrid {
        channels: 3,
        values: (0..72).map(|i| (i % 10) as f32 / 10.0).collect(),
        ..grid()
    };
    dir.write("a.vol", lucent_scene::vol::write_vol(&rgb));
    let medium = |albedo_to_world: &str| {
        scene(&format!(
            r#"    <integrator type="volpath"/>
    <shape type="cube">
        <bsdf type="null"/>
        <medium type="heterogeneous" name="interior">
            <volume name="sigma_t" type="gridvolume">
                <string name="filename" value="g.vol"/>
                <transform name="to_world"><scale value="2"/></transform>
            </volume>
            <volume name="albedo" type="gridvolume">
                <string name="filename" value="a.vol"/>
                <transform name="to_world">{albedo_to_world}</transform>
            </volume>
        </medium>
    </shape>"#
        ))
    };
    let path = dir.write("same.xml", medium(r#"<scale value="2"/>"#));
    let imported = import(&path);
    let o = objects(&imported)[0];
    let m = self::medium(&imported, o.interior.as_ref().unwrap().get_ref());
    assert_eq!(m.albedo_grid.as_ref().unwrap().get_ref(), "a.vol");
    let (_, loaded) = load(&path);
    let built = loaded.scene.medium(0);
    assert!(built.albedo_grid.is_some() && built.density.is_some());
    let text = medium(r#"<scale value="3"/>"#);
    let path = dir.write("elsewhere.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        position(&text, r#"<volume name="albedo""#),
        "the same box",
    );
}
