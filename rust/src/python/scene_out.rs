//! The inverse of `scene_dict`: a [`Scene`] as the plain dict that `beltrs.Scene.to_dict()`
//! produces (used to hand the scene stored in a checkpoint back to Python).

use crate::scene::{FrictionModel, Scene, Table, Wrap};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

fn friction<'py>(py: Python<'py>, f: &FrictionModel) -> PyResult<Option<Bound<'py, PyDict>>> {
    match *f {
        FrictionModel::None => Ok(None),
        FrictionModel::StickForce {
            static_coefficient,
            kinetic_coefficient,
        } => {
            let d = PyDict::new(py);
            d.set_item("model", "stick_force")?;
            d.set_item("static", static_coefficient)?;
            d.set_item("kinetic", kinetic_coefficient)?;
            Ok(Some(d))
        }
    }
}

fn table_into(d: &Bound<'_, PyDict>, t: &Table, xkey: &str, ykey: &str) -> PyResult<()> {
    d.set_item(xkey, t.x.clone())?;
    d.set_item(ykey, t.y.clone())
}

/// The scene as a dict with the keys of `beltrs.Scene.to_dict()`.
pub fn scene_to_dict<'py>(py: Python<'py>, s: &Scene) -> PyResult<Bound<'py, PyDict>> {
    let root = PyDict::new(py);
    let b = &s.belt;
    let belt = PyDict::new(py);
    belt.set_item("axial_stiffness", b.axial_stiffness)?;
    belt.set_item("mass_per_length", b.mass_per_length)?;
    belt.set_item("bending_stiffness", b.bending_stiffness)?;
    belt.set_item("damping_ratio", b.damping_ratio)?;
    belt.set_item("length", b.length)?;
    belt.set_item("elements", b.elements)?;
    belt.set_item("max_element_angle", b.max_element_angle)?;
    belt.set_item("tension_only", b.tension_only)?;
    belt.set_item("max_placement_strain", b.max_placement_strain)?;
    belt.set_item("formulation", b.formulation.name())?;
    root.set_item("belt", belt)?;
    let pulleys = PyList::empty(py);
    for p in &s.pulleys {
        let d = PyDict::new(py);
        d.set_item("name", &p.name)?;
        d.set_item("center", p.center.to_vec())?;
        d.set_item("radius", p.radius)?;
        d.set_item("mass", p.mass)?;
        d.set_item("inertia", p.inertia)?;
        d.set_item(
            "wrap",
            match p.wrap {
                Wrap::CounterClockwise => "ccw",
                Wrap::Clockwise => "cw",
            },
        )?;
        d.set_item("friction", friction(py, &p.friction)?)?;
        d.set_item("contact_stiffness", p.contact_stiffness)?;
        d.set_item("contact_damping", p.contact_damping)?;
        d.set_item("contact_damping_ratio", p.contact_damping_ratio)?;
        let takeup = match &p.takeup {
            None => None,
            Some(t) => {
                let td = PyDict::new(py);
                td.set_item("counterweight", t.counterweight)?;
                td.set_item("direction", t.direction.to_vec())?;
                td.set_item("travel_min", t.travel_min)?;
                td.set_item("travel_max", t.travel_max)?;
                Some(td)
            }
        };
        d.set_item("takeup", takeup)?;
        let drive = match &p.drive {
            None => None,
            Some(dr) => {
                let dd = PyDict::new(py);
                table_into(&dd, &dr.torque, "time", "torque")?;
                dd.set_item("viscous", dr.viscous)?;
                dd.set_item("inertia", dr.inertia)?;
                if !dr.speed_factor.x.is_empty() {
                    table_into(&dd, &dr.speed_factor, "speed", "speed_factor")?;
                }
                if let Some(c) = &dr.start_curve {
                    let cd = PyDict::new(py);
                    cd.set_item("shape", c.shape.name())?;
                    cd.set_item("speed", c.speed)?;
                    cd.set_item("ramp", c.ramp)?;
                    cd.set_item("start", c.start)?;
                    cd.set_item("prestart", c.prestart)?;
                    cd.set_item("creep_speed", c.creep_speed)?;
                    cd.set_item("creep_ramp", c.creep_ramp)?;
                    dd.set_item("start_curve", cd)?;
                }
                dd.set_item("max_torque", dr.max_torque)?;
                Some(dd)
            }
        };
        d.set_item("drive", drive)?;
        let brake = match &p.brake {
            None => None,
            Some(br) => {
                let bd = PyDict::new(py);
                table_into(&bd, &br.capacity, "time", "capacity")?;
                Some(bd)
            }
        };
        d.set_item("brake", brake)?;
        pulleys.append(d)?;
    }
    root.set_item("pulleys", pulleys)?;
    let idlers = PyList::empty(py);
    for k in &s.idlers {
        let d = PyDict::new(py);
        d.set_item("center", k.center.to_vec())?;
        d.set_item("radius", k.radius)?;
        d.set_item("inertia", k.inertia)?;
        d.set_item("contact_stiffness", k.contact_stiffness)?;
        d.set_item("contact_damping", k.contact_damping)?;
        d.set_item("contact_damping_ratio", k.contact_damping_ratio)?;
        d.set_item("friction", friction(py, &k.friction)?)?;
        d.set_item("resistance", k.resistance)?;
        d.set_item("rotating_mass", k.rotating_mass)?;
        idlers.append(d)?;
    }
    root.set_item("idlers", idlers)?;
    let loads = PyList::empty(py);
    for l in &s.loads {
        let d = PyDict::new(py);
        d.set_item("mass_per_length", l.mass_per_length)?;
        d.set_item("start", l.start.to_vec())?;
        d.set_item("end", l.end.to_vec())?;
        loads.append(d)?;
    }
    root.set_item("loads", loads)?;
    root.set_item("gravity", s.gravity)?;
    let solver = PyDict::new(py);
    solver.set_item("time_step", s.solver.time_step)?;
    solver.set_item("time_step_fraction", s.solver.time_step_fraction)?;
    root.set_item("solver", solver)?;
    Ok(root)
}
