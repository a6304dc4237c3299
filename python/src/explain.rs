//! A pixel's ray trees (`lucent explain`) as nested dicts.

use lucent::Rgb;
use lucent::integrator::explain::ExplainedSample;
use lucent::integrator::record::{Cut, RayNode};
use lucent::scene::Scene;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

fn rgb(c: Rgb) -> (f32, f32, f32) {
    (c.r, c.g, c.b)
}

/// A point where the scene file has it (the scene is built relative to a point near its
/// camera).
fn at(scene: &Scene, p: glam::Vec3) -> [f64; 3] {
    scene.world_point(p).to_array()
}

/// One sample: its index, film position, radiance and tree.
pub fn sample<'py>(
    py: Python<'py>,
    scene: &Scene,
    s: &ExplainedSample,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("sample", s.sample)?;
    d.set_item("through", s.through)?;
    d.set_item("radiance", rgb(s.radiance))?;
    d.set_item("tree", node(py, scene, &s.root)?)?;
    Ok(d)
}

/// A ray: what it hit, its shadow rays, its local colour, why children were not traced, and
/// its children.
fn node<'py>(py: Python<'py>, scene: &Scene, n: &RayNode) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", n.kind.name())?;
    d.set_item("origin", at(scene, n.origin))?;
    d.set_item("dir", n.dir.to_array())?;
    d.set_item("weight", rgb(n.weight))?;
    match &n.hit {
        None => d.set_item("hit", py.None())?,
        Some(h) => {
            let hit = PyDict::new(py);
            hit.set_item("t", h.t)?;
            hit.set_item("point", at(scene, h.point))?;
            hit.set_item("object", h.object)?;
            hit.set_item("material", h.material)?;
            hit.set_item("entering", h.entering)?;
            d.set_item("hit", hit)?;
        }
    }
    let lights = PyList::empty(py);
    for l in &n.lights {
        let light = PyDict::new(py);
        light.set_item("light", l.index)?;
        light.set_item("blocked", l.shadow.is_black())?;
        light.set_item("shadow", rgb(l.shadow))?;
        light.set_item("term", rgb(l.term))?;
        lights.append(light)?;
    }
    d.set_item("lights", lights)?;
    d.set_item("local", rgb(n.local))?;
    let cuts = PyList::empty(py);
    for cut in &n.cuts {
        let c = PyDict::new(py);
        match cut {
            Cut::TotalInternalReflection => c.set_item("reason", "total_internal_reflection")?,
            Cut::Depth => c.set_item("reason", "max_depth")?,
            Cut::Weight(kind, w) => {
                c.set_item("reason", "min_weight")?;
                c.set_item("ray", kind.name())?;
                c.set_item("weight", rgb(*w))?;
            }
            Cut::Budget(kind) => {
                c.set_item("reason", "budget")?;
                c.set_item("ray", kind.name())?;
            }
        }
        cuts.append(c)?;
    }
    d.set_item("cuts", cuts)?;
    d.set_item("radiance", rgb(n.radiance))?;
    d.set_item("contribution", rgb(n.contribution()))?;
    let children = PyList::empty(py);
    for child in &n.children {
        children.append(node(py, scene, child)?)?;
    }
    d.set_item("children", children)?;
    Ok(d)
}
