//! Adams View command files (`.cmd`) simulated as the solver datasets they
//! stand for: a model written as View commands moves as the same model
//! written as a dataset by hand (places relative to other frames, angles
//! in degrees, functions naming markers and elements, `modify` and
//! `active = off` commands); a part's mass from its solids agrees with the
//! closed forms of each shape (and with a quadrature for View's link);
//! what is not read is refused at its place.

use mbexpr::Location;
use mbexpr::model::FileKind;
use mbexpr::simulate::{self, Model, ModelFormat, Simulation, Unread};
use nalgebra::{Matrix3, Rotation3, Vector3};

use super::simulate::{render, settings};

/// The model of the View command file `text`; every problem as
/// `LINE:COL: message`.
fn view_model(text: &str) -> Result<Model, String> {
    simulate::from_text(text, ModelFormat::Dataset, FileKind::Cmd).map_err(|unread| match unread {
        Unread::Unchecked(problems) => problems
            .iter()
            .map(|problem| {
                let at = Location::of(text, problem.error.span().start);
                format!("{at}: {}\n", problem.error)
            })
            .collect(),
        Unread::Refused(errors) => render(text, None, &errors),
    })
}

/// The index of `model`'s output column `name` in a row.
fn column(model: &Model, name: &str) -> usize {
    simulate::columns(model)
        .iter()
        .position(|column| column == name)
        .unwrap_or_else(|| panic!("no column {name}"))
}

/// The rows of a run of `model` to `end` with `steps` output steps.
fn rows(model: &Model, end: f64, steps: usize) -> Vec<Vec<f64>> {
    let simulation = Simulation::new(model).expect("the model compiles");
    let mut rows = Vec::new();
    simulation
        .run(&settings(end, steps, 1e-10), |time, values| {
            rows.push([&[time], values].concat());
            true
        })
        .expect("the run ends");
    rows
}

/// Runs the View file `view` and the dataset `dataset` over the View
/// file's run: the same columns, and rows that agree to `tolerance`
/// (relative to values above 1). The View file's rows.
fn same_motion(view: &str, dataset: &str, tolerance: f64) -> Vec<Vec<f64>> {
    let from_view = view_model(view).unwrap_or_else(|errors| panic!("{errors}"));
    let by_hand = super::simulate::model_of(dataset).unwrap_or_else(|errors| panic!("{errors}"));
    let (end, steps) = from_view.run.expect("the View file gives its run");
    assert_eq!(simulate::columns(&from_view), simulate::columns(&by_hand));
    let (a, b) = (rows(&from_view, end, steps), rows(&by_hand, end, steps));
    // As many rows (a sensor may halt both runs), the same times.
    assert_eq!(a.len(), b.len());
    assert!(a.len() <= steps + 1);
    let mut largest = 0.0_f64;
    for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
        largest = largest.max((x - y).abs() / y.abs().max(1.0));
    }
    assert!(
        largest < tolerance,
        "the View file and the dataset differ by {largest:e}"
    );
    a
}

/// A double pendulum (the second link hung from the first's end, placed
/// relative to that marker), a crank turned by a motion, a
/// translational and a rotational spring-damper (stiffness per degree), a
/// bushing, a torque written empty and given later by `modify` (its
/// coefficient a design variable), a variable, a spline, a differential
/// equation and a request (a column a function measure), a force left
/// inactive, and View's expression definitions restating values.
const VIEW_MODEL: &str = r#"!
!-------------------------- Default Units for Model ---------------------------!
defaults units  &
   length = meter  &
   angle = deg  &
   force = newton  &
   mass = kg  &
   time = sec
!
defaults units  &
   coordinate_system_type = cartesian  &
   orientation_type = body313
!
model create  &
   model_name = m
!
defaults coordinate_system  &
   default_coordinate_system = .m.ground
!
marker create  &
   marker_name = .m.ground.G1  &
   adams_id = 1  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.ground.G2  &
   adams_id = 2  &
   location = 1.0, 1.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.ground.G3  &
   adams_id = 3  &
   location = 1.0, -1.0, 0.2  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.ground.G4  &
   adams_id = 4  &
   location = -1.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
part create rigid_body name_and_position  &
   part_name = .m.link1  &
   adams_id = 2  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
defaults coordinate_system  &
   default_coordinate_system = .m.link1
!
marker create  &
   marker_name = .m.link1.PIN  &
   adams_id = 10  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.link1.cm  &
   adams_id = 11  &
   location = 0.5, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.link1.END  &
   adams_id = 12  &
   location = 1.0, 0.0, 0.0  &
   orientation = -90.0d, 0.0d, 0.0d
!
part create rigid_body mass_properties  &
   part_name = .m.link1  &
   mass = 2.0  &
   center_of_mass_marker = .m.link1.cm  &
   ixx = 0.01  &
   iyy = 0.2  &
   izz = 0.2  &
   ixy = 0.0  &
   izx = 0.0  &
   iyz = 0.0
!
defaults coordinate_system  &
   default_coordinate_system = .m.ground
!
part create rigid_body name_and_position  &
   part_name = .m.link2  &
   adams_id = 3  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d  &
   relative_to = .m.link1.END
!
part create rigid_body initial_velocity  &
   part_name = .m.link2  &
   wz = 30.0
!
defaults coordinate_system  &
   default_coordinate_system = .m.link2
!
marker create  &
   marker_name = .m.link2.TOP  &
   adams_id = 20  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.link2.cm  &
   adams_id = 21  &
   location = 0.4, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.link2.TIP  &
   adams_id = 22  &
   location = 0.8, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
part create rigid_body mass_properties  &
   part_name = .m.link2  &
   mass = 1.0  &
   center_of_mass_marker = .m.link2.cm  &
   ixx = 0.01  &
   iyy = 0.06  &
   izz = 0.06
!
defaults coordinate_system  &
   default_coordinate_system = .m.ground
!
part create rigid_body name_and_position  &
   part_name = .m.crank  &
   adams_id = 4  &
   location = -1.0, 0.0, 0.0  &
   orientation = 90.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .m.crank.C  &
   adams_id = 30  &
   location = -1.0, 0.0, 0.0  &
   orientation = 90.0d, 0.0d, 0.0d
!
part create rigid_body mass_properties  &
   part_name = .m.crank  &
   mass = 1.0  &
   center_of_mass_marker = .m.crank.C  &
   ixx = 0.1  &
   iyy = 0.1  &
   izz = 0.1
!
constraint create joint revolute  &
   joint_name = .m.J1  &
   adams_id = 1  &
   i_marker_name = .m.link1.PIN  &
   j_marker_name = .m.ground.G1
!
constraint create joint revolute  &
   joint_name = .m.J2  &
   adams_id = 2  &
   i_marker_name = .m.link2.TOP  &
   j_marker_name = .m.link1.END
!
constraint create joint revolute  &
   joint_name = .m.J3  &
   adams_id = 3  &
   i_marker_name = .m.crank.C  &
   j_marker_name = .m.ground.G4
!
constraint create motion_generator  &
   motion_name = .m.MOTION_1  &
   adams_id = 1  &
   joint_name = .m.J3  &
   type_of_freedom = rotational  &
   time_derivative = displacement  &
   function = ""
!
force create element_like translational_spring_damper  &
   spring_damper_name = .m.SPRING  &
   adams_id = 1  &
   i_marker_name = .m.link1.END  &
   j_marker_name = .m.ground.G2  &
   stiffness = 100.0  &
   damping = 1.0  &
   preload = 5.0  &
   displacement_at_preload = 0.8
!
force create element_like rotational_spring_damper  &
   spring_damper_name = .m.TORSION  &
   adams_id = 2  &
   i_marker_name = .m.link2.TOP  &
   j_marker_name = .m.link1.END  &
   stiffness = 0.05  &
   damping = 0.001  &
   preload = 0.2  &
   displacement_at_preload = 10.0
!
force create element_like bushing  &
   bushing_name = .m.BUSH  &
   adams_id = 1  &
   i_marker_name = .m.link2.TIP  &
   j_marker_name = .m.ground.G3  &
   stiffness = 10.0, 20.0, 30.0  &
   damping = 0.1, 0.2, 0.3  &
   tstiffness = 0.01, 0.02, 0.03  &
   tdamping = 0.001, 0.001, 0.001  &
   force_preload = 0.0, 0.5, 0.0  &
   torque_preload = 0.0, 0.0, 0.1
!
force create direct single_component_force  &
   single_component_force_name = .m.DRAG  &
   adams_id = 1  &
   type_of_freedom = rotational  &
   i_marker_name = .m.link1.PIN  &
   j_marker_name = .m.ground.G1  &
   action_only = off  &
   function = ""
!
force create direct single_component_force  &
   single_component_force_name = .m.SWITCHED_OFF  &
   adams_id = 2  &
   type_of_freedom = translational  &
   i_marker_name = .m.link2.TIP  &
   j_marker_name = .m.ground.G1  &
   action_only = off  &
   function = "1E6"
!
force attributes  &
   force_name = .m.SWITCHED_OFF  &
   active = off
!
force create body gravitational  &
   gravity_field_name = gravity  &
   x_component_gravity = 0.0  &
   y_component_gravity = -9.80665  &
   z_component_gravity = 0.0
!
data_element create variable  &
   variable_name = .m.TIP_X  &
   function = "DX(.m.link2.TIP)"
!
part create equation differential_equation  &
   differential_equation_name = .m.AREA  &
   function = "VARVAL(.m.TIP_X)"  &
   initial_condition = 0.5
!
variable create  &
   variable_name = .m.drag_coefficient  &
   units = "no_units"  &
   real_value = 0.1
!
measure create function  &
   measure_name = .m.HINGE_ANGLE  &
   function = ""  &
   units = "angle"
!
data_element create spline  &
   spline_name = .m.CURVE  &
   x = 0.0, 1.0, 2.0, 3.0  &
   y = 0.0, 1.0, 4.0, 9.0  &
   linear_extrapolate = no
!
data_element create variable  &
   variable_name = .m.FROM_CURVE  &
   function = "AKISPL(time, 0, .m.CURVE, 0)"
!
output_control create request  &
   request_name = .m.REQUEST_1  &
   adams_id = 1  &
   f2 = ".m.HINGE_ANGLE"  &
   f3 = "SFORCE(.m.DRAG, 0, 6, 0)"  &
   f4 = "JOINT(J3, 0, 6, .m.ground.G4)"
!
!------------------------------ Function definitions ---------------------------!
force modify direct single_component_force  &
   single_component_force_name = .m.DRAG  &
   function = "-.m.drag_coefficient*WZ(.m.link1.PIN, .m.ground.G1)"
!
measure modify function  &
   measure_name = .m.HINGE_ANGLE  &
   function = "AZ(.m.link2.TOP, .m.link1.END)"
!
!----------------------------- Expression definitions --------------------------!
! View states again, as its own expressions, values written evaluated above.
marker modify  &
   marker_name = .m.link2.TIP  &
   location = (LOC_RELATIVE_TO({800mm, 0, 0}, .m.link2))  &
   relative_to = .m.link2
!
part modify rigid_body mass_properties  &
   part_name = .m.link1  &
   mass = (2kg)
!
force modify element_like bushing  &
   bushing_name = .m.BUSH  &
   torque_preload = 0.0, 0.0, (.m.drag_coefficient)
!
constraint modify motion_generator  &
   motion_name = .m.MOTION_1  &
   function = "30d*time"
!
simulation script create  &
   sim_script_name = .m.Last_Sim  &
   commands =   &
              "simulation single_run transient type=auto_select initial_static=no end_time=1.5 number_of_steps=30 model_name=.m"
"#;

/// The same model as the dataset a user writes by hand: the second link's
/// place and axes from the first's end, the spring's angular numbers in
/// radians, the ids View's rules give (the variable and the equation 1).
const DATASET_MODEL: &str = "the View model, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 1, 1, 0
MARKER/3, PART = 1, QP = 1, -1, 0.2
MARKER/4, PART = 1, QP = -1, 0, 0
PART/2, MASS = 2, CM = 11, IP = 0.01, 0.2, 0.2
MARKER/10, PART = 2
MARKER/11, PART = 2, QP = 0.5, 0, 0
MARKER/12, PART = 2, QP = 1, 0, 0, REULER = -90D, 0, 0
PART/3, QG = 1, 0, 0, REULER = -90D, 0, 0, MASS = 1, CM = 21, IP = 0.01, 0.06, 0.06, WZ = 0.5235987755982988
MARKER/20, PART = 3
MARKER/21, PART = 3, QP = 0.4, 0, 0
MARKER/22, PART = 3, QP = 0.8, 0, 0
PART/4, QG = -1, 0, 0, REULER = 90D, 0, 0, MASS = 1, CM = 30, IP = 0.1, 0.1, 0.1
MARKER/30, PART = 4
JOINT/1, REVOLUTE, I = 10, J = 1
JOINT/2, REVOLUTE, I = 20, J = 12
JOINT/3, REVOLUTE, I = 30, J = 4
MOTION/1, JOINT = 3, ROTATION, DISPLACEMENT, FUNCTION = 30D*TIME
SPRINGDAMPER/1, TRANSLATION, I = 12, J = 2, K = 100, C = 1, FORCE = 5, LENGTH = 0.8
SPRINGDAMPER/2, ROTATION, I = 20, J = 12, KT = 2.8647889756541161, CT = 0.057295779513082323, TORQUE = 0.2, ANGLE = 10D
BUSHING/1, I = 22, J = 3, K = 10, 20, 30, C = 0.1, 0.2, 0.3, KT = 0.57295779513082323, 1.1459155902616465, 1.7188733853924696, CT = 0.057295779513082323, 0.057295779513082323, 0.057295779513082323, FORCE = 0, 0.5, 0, TORQUE = 0, 0, 0.1
SFORCE/1, ROTATION, I = 10, J = 1, FUNCTION = -(0.1)*WZ(10, 1)
ACCGRAV/JGRAV = -9.80665
VARIABLE/1, FUNCTION = DX(22)
SPLINE/1, X = 0, 1, 2, 3, Y = 0, 1, 4, 9
VARIABLE/2, FUNCTION = AKISPL(TIME, 0, 1, 0)
DIFF/1, FUNCTION = VARVAL(1), IC = 0.5
REQUEST/1, F2 = (AZ(20, 12)), F3 = SFORCE(1, 0, 6, 0), F4 = JOINT(3, 0, 6, 4)
VARIABLE/3, FUNCTION = AZ(20, 12)
END
";

/// The View file and the dataset written by hand give the same columns
/// and the same rows, to the integration tolerance; the run is the
/// script's (1.5 s, 30 steps).
#[test]
fn a_view_file_moves_as_the_dataset_it_stands_for() {
    let rows = same_motion(VIEW_MODEL, DATASET_MODEL, 1e-7);
    assert_eq!(rows.len(), 31);
    assert_eq!(rows.last().map(|row| row[0]), Some(1.5));
    // The run moved: the crank turned 45 degrees, the link swung.
    assert!(rows[0] != rows[30]);
    // The dataset mbexpr writes for the View file (`simulate --dataset`)
    // is the model it simulates: read back, it moves as the View file.
    let (exported, _) = simulate::view_dataset_text(VIEW_MODEL).unwrap_or_else(|_| panic!("read"));
    same_motion(VIEW_MODEL, &exported, 1e-12);
}

/// A part of `density` with the solids `geometry` (commands placed on its
/// markers `M1` at (1, 2, 3) turned 30° about z then 40° about x, and
/// `M2` at the origin, the part at (0.5, 0, 0) turned 90° about z): its
/// mass, its centre in the part's frame, and its inertia about the centre
/// in the part's axes.
fn solid_mass(density: f64, geometry: &str) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let text = format!(
        "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = s
material create material_name = .s.stuff density = {density}
part create rigid_body name_and_position part_name = .s.body adams_id = 2 location = 0.5, 0, 0 orientation = 90d, 0d, 0d
marker create marker_name = .s.body.M1 adams_id = 1 location = 1, 2, 3 orientation = 30d, 40d, 0d relative_to = .s.ground
marker create marker_name = .s.body.M2 adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d relative_to = .s.ground
part create rigid_body mass_properties part_name = .s.body material_type = .s.stuff
{geometry}
"
    );
    let model = view_model(&text).unwrap_or_else(|errors| panic!("{errors}"));
    let mass = &model.masses[0];
    (mass.mass, mass.centre, mass.inertia)
}

/// The axes of marker `M1` in the part's axes, and its origin in the part.
fn m1_in_part() -> (Matrix3<f64>, Vector3<f64>) {
    let part = Rotation3::from_axis_angle(&Vector3::z_axis(), 90f64.to_radians());
    let marker = Rotation3::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians())
        * Rotation3::from_axis_angle(&Vector3::x_axis(), 40f64.to_radians());
    let axes = part.inverse() * marker;
    let origin = part.inverse() * (Vector3::new(1.0, 2.0, 3.0) - Vector3::new(0.5, 0.0, 0.0));
    (axes.into_inner(), origin)
}

/// The largest difference of two mass properties, relative to their size.
fn differs(
    (mass, centre, inertia): (f64, Vector3<f64>, Matrix3<f64>),
    (mass_0, centre_0, inertia_0): (f64, Vector3<f64>, Matrix3<f64>),
    size: f64,
) -> f64 {
    ((mass - mass_0).abs() / mass_0)
        .max((centre - centre_0).amax() / size)
        .max((inertia - inertia_0).amax() / inertia_0.amax())
}

/// A solid on `M1` whose inertia about its centre, in `M1`'s axes, is
/// the diagonal `moments`, its centre at `centre` in `M1`'s frame: its
/// mass properties in the part.
fn on_m1(mass: f64, centre: Vector3<f64>, moments: [f64; 3]) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let (axes, origin) = m1_in_part();
    let inertia = axes * Matrix3::from_diagonal(&Vector3::from(moments)) * axes.transpose();
    (mass, origin + axes * centre, inertia)
}

/// Each solid's mass properties against its closed form: a block from its
/// corner marker, a cylinder, a cone frustum, an ellipsoid of diameters
/// and a torus on their centre markers, all turned and moved.
#[test]
fn a_parts_mass_from_its_solids_agrees_with_the_closed_forms() {
    let density = 2.5;
    let (a, b, c) = (0.3, 0.2, 0.7);
    let m = density * a * b * c;
    let block = solid_mass(
        density,
        &format!(
            "geometry create shape block block_name = .s.body.B corner_marker = .s.body.M1 diag_corner_coords = {a}, {b}, {c}"
        ),
    );
    let expected = on_m1(
        m,
        Vector3::new(a, b, c) / 2.0,
        [
            m * (b * b + c * c) / 12.0,
            m * (a * a + c * c) / 12.0,
            m * (a * a + b * b) / 12.0,
        ],
    );
    assert!(differs(block, expected, 1.0) < 1e-12, "block");

    let (r, l) = (0.1, 0.6);
    let m = density * std::f64::consts::PI * r * r * l;
    let cylinder = solid_mass(
        density,
        &format!(
            "geometry create shape cylinder cylinder_name = .s.body.C center_marker = .s.body.M1 angle_extent = 360.0 length = {l} radius = {r}"
        ),
    );
    let side = m * (3.0 * r * r + l * l) / 12.0;
    let expected = on_m1(
        m,
        Vector3::new(0.0, 0.0, l / 2.0),
        [side, side, m * r * r / 2.0],
    );
    assert!(differs(cylinder, expected, 1.0) < 1e-12, "cylinder");

    // A cone frustum: volume, centroid and axial moment in closed form;
    // the moment across from 20 000 discs.
    let (r1, r2, l) = (0.2, 0.05, 0.5);
    let pi = std::f64::consts::PI;
    let volume = pi * l * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0;
    let m = density * volume;
    let z_bar =
        l * (r1 * r1 + 2.0 * r1 * r2 + 3.0 * r2 * r2) / (4.0 * (r1 * r1 + r1 * r2 + r2 * r2));
    let axial = 0.3 * m * (r1.powi(5) - r2.powi(5)) / (r1.powi(3) - r2.powi(3));
    let slices = 20_000;
    let across: f64 = (0..slices)
        .map(|k| {
            let z = (k as f64 + 0.5) / slices as f64 * l;
            let radius = r1 + (r2 - r1) * z / l;
            let disc = density * pi * radius * radius * l / slices as f64;
            disc * (radius * radius / 4.0 + (z - z_bar) * (z - z_bar))
        })
        .sum();
    let frustum = solid_mass(
        density,
        &format!(
            "geometry create shape frustum frustum_name = .s.body.F center_marker = .s.body.M1 angle_extent = 360.0 length = {l} bottom_radius = {r1} top_radius = {r2}"
        ),
    );
    let expected = on_m1(m, Vector3::new(0.0, 0.0, z_bar), [across, across, axial]);
    assert!(differs(frustum, expected, 1.0) < 1e-8, "frustum");

    let (dx, dy, dz) = (0.4, 0.3, 0.2);
    let (ax, ay, az) = (dx / 2.0, dy / 2.0, dz / 2.0);
    let m = density * 4.0 / 3.0 * pi * ax * ay * az;
    let ellipsoid = solid_mass(
        density,
        &format!(
            "geometry create shape ellipsoid ellipsoid_name = .s.body.E center_marker = .s.body.M1 x_scale_factor = {dx} y_scale_factor = {dy} z_scale_factor = {dz}"
        ),
    );
    let expected = on_m1(
        m,
        Vector3::zeros(),
        [
            m * (ay * ay + az * az) / 5.0,
            m * (ax * ax + az * az) / 5.0,
            m * (ax * ax + ay * ay) / 5.0,
        ],
    );
    assert!(differs(ellipsoid, expected, 1.0) < 1e-12, "ellipsoid");

    let (major, minor) = (0.5, 0.1);
    let m = density * 2.0 * pi * pi * major * minor * minor;
    let torus = solid_mass(
        density,
        &format!(
            "geometry create shape torus torus_name = .s.body.T center_marker = .s.body.M1 angle_extent = 360.0 major_radius = {major} minor_radius = {minor}"
        ),
    );
    let side = m * (major * major / 2.0 + 5.0 * minor * minor / 8.0);
    let expected = on_m1(
        m,
        Vector3::zeros(),
        [side, side, m * (major * major + 0.75 * minor * minor)],
    );
    assert!(differs(torus, expected, 1.0) < 1e-12, "torus");
}

/// View's link (a bar with rounded ends, `width` across, `depth` thick)
/// from `M2` at the ground's origin to `M1`, against a quadrature of its
/// outline on a fine grid; each end is half of the regular 20-gon
/// inscribed in the end's circle, as View rounds it (its export of a
/// user's link, below, holds the 20-gon's mass and moments to ten
/// digits); two solids on one part add.
#[test]
fn a_links_mass_agrees_with_a_quadrature_of_its_outline() {
    let density = 3.0;
    let (width, depth) = (0.2, 0.05);
    let link = solid_mass(
        density,
        &format!(
            "geometry create shape link link_name = .s.body.L i_marker = .s.body.M2 j_marker = .s.body.M1 width = {width} depth = {depth}"
        ),
    );
    // The link's frame: x from M2 to M1, z the z axis of M2 (the ground's).
    let end = Vector3::new(1.0, 2.0, 3.0);
    let in_plane = Vector3::new(end.x, end.y, 0.0);
    // M1 is off M2's xy plane: View asks for it on it; the link lies along
    // its projection's direction in 3-D, with z made square to x.
    let x = end.normalize();
    let z = (Vector3::z() - x * x.z).normalize();
    let y = z.cross(&x);
    let length = end.norm();
    let radius = width / 2.0;
    let cells = 1500;
    let (mut area, mut first, mut xx, mut yy) = (0.0, 0.0, 0.0, 0.0);
    let (span_x, span_y) = (length + width, width);
    let cell = span_x / cells as f64 * (span_y / (cells / 5) as f64);
    for i in 0..cells {
        let u = -radius + (i as f64 + 0.5) / cells as f64 * span_x;
        for j in 0..cells / 5 {
            let v = -radius + (j as f64 + 0.5) / (cells / 5) as f64 * span_y;
            // Inside the 20-gon about (cx, 0) whose vertices lie at
            // ±90° + 18° k: within its apothem along each side's normal.
            let in_polygon = |cx: f64| {
                (0..20).all(|k| {
                    let normal = (99.0 + 18.0 * f64::from(k)).to_radians();
                    (u - cx) * normal.cos() + v * normal.sin() <= radius * 9f64.to_radians().cos()
                })
            };
            let inside = (0.0..=length).contains(&u) || in_polygon(0.0) || in_polygon(length);
            if inside {
                area += cell;
                first += u * cell;
                xx += u * u * cell;
                yy += v * v * cell;
            }
        }
    }
    let m = density * area * depth;
    let u_bar = first / area;
    let about_centre = [
        // about x: across (y) and through the depth (z)
        density * depth * yy + m * depth * depth / 12.0,
        density * depth * (xx - area * u_bar * u_bar) + m * depth * depth / 12.0,
        density * depth * (xx - area * u_bar * u_bar + yy),
    ];
    let axes = Matrix3::from_columns(&[x, y, z]);
    let part = Rotation3::from_axis_angle(&Vector3::z_axis(), 90f64.to_radians());
    let in_part = part.inverse().into_inner() * axes;
    let centre = part.inverse() * (x * u_bar - Vector3::new(0.5, 0.0, 0.0));
    let expected = (
        m,
        centre,
        in_part * Matrix3::from_diagonal(&Vector3::from(about_centre)) * in_part.transpose(),
    );
    assert!(in_plane.norm() > 0.0);
    assert!(
        differs(link, expected, 1.0) < 2e-3,
        "link: {:e}",
        differs(link, expected, 1.0)
    );
    // A user's link (Radka208677/RL_with_Continuous_Action_Space,
    // pendulum.cmd: 100 mm long, 10 wide, 5 deep, steel of 7.801e-6
    // kg/mm³) and the mass and moments Adams View exported for it
    // (pendulum.adm: MASS = 0.042018302, IP = 41.03368968, 40.77766026,
    // 0.4311056795 about its centre).
    let text = "defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = s
material create material_name = .s.steel density = 7.801E-06
part create rigid_body name_and_position part_name = .s.body adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .s.body.M1 adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .s.body.M2 adams_id = 2 location = 0, -100, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .s.body material_type = .s.steel
geometry create shape link link_name = .s.body.L i_marker = .s.body.M1 j_marker = .s.body.M2 width = 10.0 depth = 5.0
";
    let model = view_model(text).unwrap_or_else(|errors| panic!("{errors}"));
    let mass = &model.masses[0];
    // mbexpr holds masses divided by the units consistency factor (1000
    // for mm, kg, N).
    let units = 1000.0;
    assert!(
        (mass.mass * units - 0.042018302).abs() < 1e-9,
        "{}",
        mass.mass
    );
    // The part's axes are the link's principal axes: the moments, smallest
    // first (about the link's length, across it in its plane, through it).
    let mut ours: Vec<f64> = (0..3).map(|k| mass.inertia[(k, k)] * units).collect();
    ours.sort_by(f64::total_cmp);
    for (ours, view) in ours
        .into_iter()
        .zip([0.4311056795, 40.77766026, 41.03368968])
    {
        assert!(
            (ours - view).abs() < 2e-9 * view.max(1.0),
            "{ours} against {view}"
        );
    }

    // A block and a sphere on one part: their sum about the common centre.
    let block = "geometry create shape block block_name = .s.body.B corner_marker = .s.body.M2 diag_corner_coords = 0.2, 0.2, 0.2";
    let sphere = "geometry create shape ellipsoid ellipsoid_name = .s.body.E center_marker = .s.body.M1 x_scale_factor = 0.4 y_scale_factor = 0.4 z_scale_factor = 0.4";
    let (m1, c1, i1) = solid_mass(density, block);
    let (m2, c2, i2) = solid_mass(density, sphere);
    let both = solid_mass(density, &format!("{block}\n{sphere}"));
    let centre = (c1 * m1 + c2 * m2) / (m1 + m2);
    let shift = |m: f64, d: Vector3<f64>| (Matrix3::identity() * d.dot(&d) - d * d.transpose()) * m;
    let inertia = i1 + shift(m1, c1 - centre) + i2 + shift(m2, c2 - centre);
    assert!(
        differs(both, (m1 + m2, centre, inertia), 1.0) < 1e-12,
        "block and sphere"
    );
}

/// What a View file's reading refuses or finds wrong, at its place.
fn check(text: &str) -> String {
    let text = format!("model create model_name = m\n{text}\n");
    match view_model(&text) {
        Ok(model) => format!(
            "read: {} bodies, {} notes",
            model.masses.len(),
            model.notes.len()
        ),
        Err(errors) => errors.trim_end().replace('\n', "\n     "),
    }
}

#[test]
fn what_is_refused_is_refused_at_its_place() {
    let part = "part create rigid_body name_and_position part_name = .m.P\nmarker create marker_name = .m.P.A\npart create rigid_body mass_properties part_name = .m.P mass = 1 center_of_mass_marker = .m.P.A ixx = 1 iyy = 1 izz = 1";
    let cases = [
        // The whole file reads: one body.
        part.to_string(),
        format!("{part}\nforce create element_like field field_name = .m.FIELD"),
        format!(
            "{part}\ngeometry create shape ellipsoid ellipsoid_name = .m.P.S center_marker = .m.P.A x_scale_factor = 1 y_scale_factor = 1 z_scale_factor = 1\ncontact create contact_name = .m.C i_geometry_name = .m.P.S j_geometry_name = .m.P.S penalty = 1e5 restitution_coefficient = 0.5"
        ),
        format!(
            "{part}\ngeometry create shape torus torus_name = .m.P.T center_marker = .m.P.A major_radius = 1 minor_radius = 0.1\ncontact create contact_name = .m.C i_geometry_name = .m.P.T j_geometry_name = .m.ground.NONE stiffness = 1e5 damping = 10 exponent = 2.2 dmax = 0.1"
        ),
        format!(
            "{part}\nforce create direct single_component_force single_component_force_name = .m.F i_marker_name = .m.P.A j_marker_name = .m.ground.X function = \"1\""
        ),
        format!(
            "{part}\nforce create direct single_component_force single_component_force_name = .m.F i_marker_name = .m.P.A j_marker_name = .m.P.A function = \"\""
        ),
        format!(
            "{part}\ndata_element create variable variable_name = .m.V function = \"2*.m.DV_1\""
        ),
        format!("{part}\npart create rigid_body name_and_position part_name = .m.Q planar = yes"),
        format!(
            "{part}\nconstraint create joint revolute joint_name = .m.J i_marker_name = .m.P.A j_marker_name = .m.P.A delta_v = 2"
        ),
        format!("{part}\nmarker create marker_name = .m.P.B location = (.m.DV_2), 0, 0"),
        format!("{part}\ndefaults units length = furlong"),
        // View's general motion, a library constraint: it would drive the
        // part, so it is refused, not passed over.
        format!(
            "{part}\nude create instance instance_name = .m.general_motion_1 definition_name = .MDI.Constraints.general_motion\nvariable modify variable_name = .m.general_motion_1.r3_type integer_value = 1"
        ),
        // An Adams Machinery element (a motor, a cam): its definition
        // makes parts and forces; refused, not passed over.
        format!(
            "{part}\nude create instance instance_name = .m.motor_1 definition_name = .amachinery.parts.ac_motor_external"
        ),
        format!(
            "{part}\nsimulation single_run statics\nmarker attributes marker_name = .m.P.A active = off"
        ),
        format!(
            "{part}\nmaterial create material_name = .m.steel density = 7.8e-6\ngeometry create shape revolution revolution_name = .m.P.E\npart modify rigid_body mass_properties part_name = .m.P material_type = .m.steel"
        ),
    ];
    let report: String = cases
        .iter()
        .map(|case| {
            format!(
                "{}\n  => {}\n",
                case.lines().last().unwrap_or_default(),
                check(case)
            )
        })
        .collect();
    insta::assert_snapshot!(report);
}

/// A steel ball (its mass from its sphere) dropped on a block of ground
/// through a contact with friction, written as View commands, and the
/// same written by hand as a dataset: the same rows.
#[test]
fn a_contact_between_view_solids_acts_as_the_datasets() {
    let view = r#"defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = drop
material create material_name = .drop.steel density = 7.801E-06
defaults coordinate_system default_coordinate_system = .drop.ground
marker create marker_name = .drop.ground.CORNER adams_id = 1 location = -100, -20, -100 orientation = 0d, 0d, 0d
geometry create shape block block_name = .drop.ground.TABLE adams_id = 7 corner_marker = .drop.ground.CORNER diag_corner_coords = 200, 20, 200
part create rigid_body name_and_position part_name = .drop.ball adams_id = 2 location = 0, 30, 0 orientation = 0d, 0d, 0d
part create rigid_body initial_velocity part_name = .drop.ball vx = 50
defaults coordinate_system default_coordinate_system = .drop.ball
marker create marker_name = .drop.ball.CENTRE adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .drop.ball material_type = .drop.steel
geometry create shape ellipsoid ellipsoid_name = .drop.ball.SPHERE center_marker = .drop.ball.CENTRE x_scale_factor = 20 y_scale_factor = 20 z_scale_factor = 20
contact create contact_name = .drop.CONTACT_1 adams_id = 1 i_geometry_name = .drop.ball.SPHERE j_geometry_name = .drop.ground.TABLE stiffness = 1.0E+05 damping = 10.0 exponent = 2.2 dmax = 0.1 coulomb_friction = on mu_static = 0.3 mu_dynamic = 0.1 stiction_transition_velocity = 100 friction_transition_velocity = 1000
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9806.65 z_component_gravity = 0
simulation single_run transient end_time = 0.3 number_of_steps = 30
"#;
    let pi = std::f64::consts::PI;
    let mass = 7.801e-6 * 4.0 / 3.0 * pi * 1000.0;
    let moment = 0.4 * mass * 100.0;
    let dataset = format!(
        "the dropped ball, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = MILLIMETER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1, QP = -100, -20, -100
GRAPHICS/7, BOX, CORNER = 1, X = 200, Y = 20, Z = 200
PART/2, QG = 0, 30, 0, MASS = {mass}, CM = 2, IP = {moment}, {moment}, {moment}, VX = 50
MARKER/2, PART = 2
GRAPHICS/1, ELLIPSOID, CM = 2, XSCALE = 20, YSCALE = 20, ZSCALE = 20
CONTACT/1, IGEOM = 1, JGEOM = 7, IMPACT, STIFFNESS = 1E5, DAMPING = 10, EXPONENT = 2.2, DMAX = 0.1, COULOMB_FRICTION = ON, MU_STATIC = 0.3, MU_DYNAMIC = 0.1, STICTION_TRANSITION_VELOCITY = 100, FRICTION_TRANSITION_VELOCITY = 1000
ACCGRAV/JGRAV = -9806.65
END
"
    );
    let a = same_motion(view, &dataset, 1e-6);
    assert_eq!(a.len(), 31);
    // The ball landed and rests on the table (its centre 10 mm above it),
    // sliding on with friction slowing it.
    let last = a.last().expect("rows");
    assert!(
        (last[2] - 10.0).abs() < 0.1,
        "the ball's height {}",
        last[2]
    );
    assert!(last[8] < 50.0 && last[8] > 0.0, "its speed {}", last[8]);
}

/// A cantilever BEAM in View's words (its section's area, moments and
/// moduli) bends a tip mass as the dataset's BEAM does.
#[test]
fn a_view_beam_is_the_datasets_beam() {
    let view = "defaults units length = meter angle = rad force = newton mass = kg time = sec
model create model_name = b
marker create marker_name = .b.ground.ROOT adams_id = 1 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body name_and_position part_name = .b.tip adams_id = 2 location = 1, 0, 0 orientation = 0, 0, 0
part create rigid_body initial_velocity part_name = .b.tip vy = 0.3 wx = 2
marker create marker_name = .b.tip.END adams_id = 2 location = 1, 0, 0 orientation = 0, 0, 0 relative_to = .b.ground
part create rigid_body mass_properties part_name = .b.tip mass = 2 center_of_mass_marker = .b.tip.END ixx = 0.01 iyy = 0.01 izz = 0.01
force create element_like beam beam_name = .b.BEAM_1 adams_id = 3 i_marker_name = .b.tip.END j_marker_name = .b.ground.ROOT length = 1 area_of_cross_section = 1e-4 y_shear_area_ratio = 1.2 z_shear_area_ratio = 1.2 youngs_modulus = 2e9 shear_modulus = 8e8 ixx = 2e-9 iyy = 1e-9 izz = 1e-9 damping_ratio = 0.01
simulation single_run transient end_time = 0.5 number_of_steps = 25
";
    let dataset = "the cantilever, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, QG = 1, 0, 0, MASS = 2, CM = 2, IP = 0.01, 0.01, 0.01, VY = 0.3, WX = 2
MARKER/2, PART = 2
BEAM/3, I = 2, J = 1, LENGTH = 1, AREA = 1e-4, ASY = 1.2, ASZ = 1.2, EMODULUS = 2e9, GMODULUS = 8e8, IXX = 2e-9, IYY = 1e-9, IZZ = 1e-9, CRATIO = 0.01
END
";
    let rows = same_motion(view, dataset, 1e-7);
    // The tip swings: it moved across.
    assert!(rows.iter().any(|row| row[2].abs() > 1e-3));
}

/// Two wheels geared by a View coupler (`constraint create complex_joint
/// coupler`, its motion multipliers Adams' SCALES), and a third part made
/// inactive with the joint and force on it: as the dataset without them.
#[test]
fn a_view_coupler_and_an_inactive_part() {
    let view = "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = g
marker create marker_name = .g.ground.A adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.ground.B adams_id = 2 location = 1, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.ground.C adams_id = 3 location = 2, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body name_and_position part_name = .g.wheel_1 adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.wheel_1.M adams_id = 20 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .g.wheel_1 mass = 1 center_of_mass_marker = .g.wheel_1.M ixx = 1 iyy = 1 izz = 0.5
part create rigid_body name_and_position part_name = .g.wheel_2 adams_id = 3 location = 1, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.wheel_2.M adams_id = 30 location = 1, 0, 0 orientation = 0d, 0d, 0d relative_to = .g.ground
part create rigid_body mass_properties part_name = .g.wheel_2 mass = 1 center_of_mass_marker = .g.wheel_2.M ixx = 1 iyy = 1 izz = 0.2
part create rigid_body name_and_position part_name = .g.spare adams_id = 4 location = 2, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.spare.M adams_id = 40 location = 2, 0, 0 orientation = 0d, 0d, 0d relative_to = .g.ground
part create rigid_body mass_properties part_name = .g.spare mass = 1 center_of_mass_marker = .g.spare.M ixx = 1 iyy = 1 izz = 1
constraint create joint revolute joint_name = .g.J1 adams_id = 1 i_marker_name = .g.wheel_1.M j_marker_name = .g.ground.A
constraint create joint revolute joint_name = .g.J2 adams_id = 2 i_marker_name = .g.wheel_2.M j_marker_name = .g.ground.B
constraint create joint fixed joint_name = .g.J3 adams_id = 3 i_marker_name = .g.spare.M j_marker_name = .g.ground.C
constraint create complex_joint coupler coupler_name = .g.COUPLER_1 adams_id = 1 joint_name = .g.J1, .g.J2 type_of_freedom = rot_rot motion_multipliers = 1.0, 2.7
force create direct single_component_force single_component_force_name = .g.TORQUE adams_id = 1 type_of_freedom = rotational action_only = on i_marker_name = .g.wheel_1.M j_marker_name = .g.ground.A function = \"3.0\"
force create direct single_component_force single_component_force_name = .g.PUSH adams_id = 2 type_of_freedom = translational action_only = on i_marker_name = .g.spare.M j_marker_name = .g.ground.A function = \"1E6\"
part attributes part_name = .g.spare active = off
simulation single_run transient end_time = 1 number_of_steps = 10
";
    let dataset = "the geared wheels, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 1, 0, 0
MARKER/3, PART = 1, QP = 2, 0, 0
PART/2, MASS = 1, CM = 20, IP = 1, 1, 0.5
MARKER/20, PART = 2
PART/3, QG = 1, 0, 0, MASS = 1, CM = 30, IP = 1, 1, 0.2
MARKER/30, PART = 3
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, REVOLUTE, I = 30, J = 2
COUPLER/1, JOINTS = 1, 2, TYPE = R:R, SCALES = 1, 2.7
SFORCE/1, ROTATION, ACTIONONLY, I = 20, J = 1, FUNCTION = 3.0
END
";
    let rows = same_motion(view, dataset, 1e-8);
    // The first wheel turns under the torque: AZ1 + 2.7 AZ2 = 0, so its
    // reflected inertia is 0.5 + 0.2 / 2.7².
    let alpha = 3.0 / (0.5 + 0.2 / (2.7 * 2.7));
    let last = rows.last().expect("rows");
    let turn = 2.0 * (last[7] / last[4]).atan();
    assert!((turn - 0.5 * alpha).abs() < 1e-6, "the wheel turned {turn}");
}

/// `examples/simulate/n_view_four_bar.cmd`, a four-bar linkage as View
/// exports it (links whose mass View computes from their geometry, four
/// revolute joints, a motion turning the crank once a second): its run
/// is the script's, and the rocker's angle (REQUEST F2, in degrees)
/// follows the linkage's closed-form position at every row.
#[test]
fn the_view_four_bar_follows_its_closed_form() {
    let text = include_str!("../examples/simulate/n_view_four_bar.cmd");
    let model = view_model(text).unwrap_or_else(|errors| panic!("{errors}"));
    assert_eq!(model.run, Some((1.0, 20)));
    let angle = column(&model, "REQUEST/1.F2");
    let (a, d): (Vector3<f64>, Vector3<f64>) = (Vector3::zeros(), Vector3::new(400.0, 0.0, 0.0));
    let (b0, c0) = (
        Vector3::new(0.0, 100.0, 0.0),
        Vector3::new(300.0, 250.0, 0.0),
    );
    let (coupler, rocker) = ((c0 - b0).norm(), (c0 - d).norm());
    let start = (c0.y - d.y).atan2(c0.x - d.x);
    let mut c = c0;
    let mut largest = 0.0_f64;
    for row in rows(&model, 1.0, 20) {
        let crank = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * row[0];
        let b = a + Vector3::new(crank.cos(), crank.sin(), 0.0) * 100.0;
        // C on the circles about B and D: of the two, the one nearer the
        // last (the linkage does not pass a toggle).
        let (between, distance) = (d - b, (d - b).norm());
        let along = (coupler * coupler - rocker * rocker + distance * distance) / (2.0 * distance);
        let across = (coupler * coupler - along * along).sqrt();
        let unit = between / distance;
        let normal = Vector3::new(-unit.y, unit.x, 0.0);
        let candidates = [
            b + unit * along + normal * across,
            b + unit * along - normal * across,
        ];
        c = if (candidates[0] - c).norm() < (candidates[1] - c).norm() {
            candidates[0]
        } else {
            candidates[1]
        };
        let turned = ((c.y - d.y).atan2(c.x - d.x) - start).to_degrees();
        let wrapped = (turned + 180.0).rem_euclid(360.0) - 180.0;
        largest = largest.max((row[angle] - wrapped).abs());
    }
    assert!(
        largest < 1e-4,
        "the rocker is off its closed form by {largest:e} degrees"
    );
}

/// Function measures that read one another in a loop, or a chain of
/// thousands, stop with a message, not a stack overflow.
#[test]
fn measures_in_a_loop_or_a_long_chain_stop_with_a_message() {
    let mut text = String::from("model create model_name = m\n");
    text.push_str("measure create function measure_name = .m.A function = \".m.B + 1\"\n");
    text.push_str("measure create function measure_name = .m.B function = \".m.A + 1\"\n");
    text.push_str("data_element create variable variable_name = .m.V function = \".m.A\"\n");
    let looped = view_model(&text).expect_err("a loop is refused");
    assert!(looped.contains("read one another in a loop"), "{looped}");
    let mut chain = String::from("model create model_name = m\n");
    for k in 0..5000 {
        chain.push_str(&format!(
            "measure create function measure_name = .m.M{k} function = \".m.M{} + 1\"\n",
            k + 1
        ));
    }
    chain.push_str("measure create function measure_name = .m.M5000 function = \"1\"\n");
    chain.push_str("data_element create variable variable_name = .m.V function = \".m.M0\"\n");
    let long = view_model(&chain).expect_err("a chain of 5000 is refused");
    assert!(long.contains("32 deep"), "{long}");
}

/// A joint's friction (`force create element_like friction`) and its
/// initial conditions in View's words: a wheel on a revolute pin, set at
/// 30° and turning at 180°/s (`rotational_ic`, `angular_velocity_ic`),
/// braked by a friction of its torque preload alone (the reaction force
/// and bending moment turned off), moves as the dataset by hand and as
/// the closed form θ = θ0 + ω0 t − ½ μd T0 / Izz t².
#[test]
fn a_view_friction_and_a_joints_initial_conditions_are_the_datasets() {
    let view = r#"defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = w
marker create marker_name = .w.ground.PIN adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body name_and_position part_name = .w.wheel adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .w.wheel.HUB adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .w.wheel mass = 3 center_of_mass_marker = .w.wheel.HUB ixx = 0.2 iyy = 0.2 izz = 0.4
constraint create joint revolute joint_name = .w.PIN_JOINT adams_id = 1 i_marker_name = .w.wheel.HUB j_marker_name = .w.ground.PIN rotational_ic = 30 angular_velocity_ic = 180
force create element_like friction friction_name = .w.FRICTION_1 adams_id = 1 joint_name = .w.PIN_JOINT mu_static = 0.3 mu_dynamic = 0.2 friction_arm = 1.0 bending_reaction_arm = 1.0 pin_radius = 0.05 stiction_transition_velocity = 1.0E-03 max_stiction_deformation = 1.0E-04 friction_torque_preload = 2 effect = all preload = on reaction_force = off bending_moment = off inactive_during_static = on
output_control create request request_name = .w.ANGLE adams_id = 1 f2 = "AZ(.w.wheel.HUB, .w.ground.PIN)" f3 = "WZ(.w.wheel.HUB, .w.ground.PIN, .w.ground.PIN)"
simulation single_run transient end_time = 0.9 number_of_steps = 9
"#;
    let dataset = "the braked wheel, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 3, CM = 2, IP = 0.2, 0.2, 0.4
MARKER/2, PART = 2
JOINT/1, REVOLUTE, I = 2, J = 1, IC = 3.141592653589793, 0.5235987755982988
FRICTION/1, JOINT = 1, MU_STATIC = 0.3, MU_DYNAMIC = 0.2, FRICTION_ARM = 1, BENDING_REACTION_ARM = 1, PIN_RADIUS = 0.05, STICTION_TRANSITION_VELOCITY = 1E-3, MAX_STICTION_DEFORMATION = 1E-4, FRICTION_TORQUE_PRELOAD = 2, EFFECT = ALL, INPUTS = PRELOAD, INACTIVE = STATIC
REQUEST/1, F2 = AZ(2, 1)\\F3 = WZ(2, 1, 1)
END
";
    let rows = same_motion(view, dataset, 1e-7);
    let model = view_model(view).expect("the model");
    let [angle, speed] = ["REQUEST/1.F2", "REQUEST/1.F3"].map(|name| column(&model, name));
    // The brake's torque μd T0 on Izz: the wheel stops at 1 s, after the run.
    let alpha = 0.2 * 2.0 / 0.4;
    let (start, spin) = (30_f64.to_radians(), 180_f64.to_radians());
    for row in &rows {
        let t = row[0];
        let (theta, omega) = (start + spin * t - 0.5 * alpha * t * t, spin - alpha * t);
        assert!(
            (row[angle] - theta).abs() < 1e-6 && (row[speed] - omega).abs() < 1e-6,
            "at {t}: the wheel at {} turning {}, the closed form {theta}, {omega}",
            row[angle],
            row[speed]
        );
    }
}

/// A crate on a slope of 20° (a translational joint along it) launched up
/// it by its joint's velocity alone (`velocity_ic`, the displacement left
/// to the assembly), slowed by its friction on the joint's reaction: it
/// slides up as s = v0 t − ½ g (sin α + μd cos α) t², stops, and stays
/// (μs above tan α).
#[test]
fn a_crate_launched_by_its_joints_velocity_slides_up_and_stays() {
    let view = r#"defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = c
marker create marker_name = .c.ground.RAIL adams_id = 1 location = 0, 0, 0 orientation = 110d, 90d, 0d
part create rigid_body name_and_position part_name = .c.crate adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .c.crate.SHOE adams_id = 2 location = 0, 0, 0 orientation = 110d, 90d, 0d
part create rigid_body mass_properties part_name = .c.crate mass = 5 center_of_mass_marker = .c.crate.SHOE ixx = 1 iyy = 1 izz = 1
constraint create joint translational joint_name = .c.SLIDE adams_id = 1 i_marker_name = .c.crate.SHOE j_marker_name = .c.ground.RAIL velocity_ic = 2.0
force create element_like friction friction_name = .c.FRICTION_1 adams_id = 1 joint_name = .c.SLIDE mu_static = 0.5 mu_dynamic = 0.3 reaction_arm = 1.0 initial_overlap = 1000.0 formulation = original stiction_transition_velocity = 1.0E-03 transition_velocity_coefficient = 1.5 max_stiction_deformation = 1.0E-05 friction_force_preload = 0.0 overlap_delta = constant effect = all preload = on reaction_force = on torsional_moment = off bending_moment = off inactive_during_static = off
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9.80665 z_component_gravity = 0
output_control create request request_name = .c.SLIDING adams_id = 1 f2 = "DZ(.c.crate.SHOE, .c.ground.RAIL, .c.ground.RAIL)" f3 = "VZ(.c.crate.SHOE, .c.ground.RAIL, .c.ground.RAIL, .c.ground.RAIL)"
simulation single_run transient end_time = 1.0 number_of_steps = 20
"#;
    let model = view_model(view).unwrap_or_else(|errors| panic!("{errors}"));
    let [along, speed] = ["REQUEST/1.F2", "REQUEST/1.F3"].map(|name| column(&model, name));
    let slope = 20_f64.to_radians();
    let braking = 9.80665 * (slope.sin() + 0.3 * slope.cos());
    let stop = 2.0 / braking;
    let top = 2.0 * stop - 0.5 * braking * stop * stop;
    for row in rows(&model, 1.0, 20) {
        let t = row[0];
        let (s, v) = if t < stop {
            (2.0 * t - 0.5 * braking * t * t, 2.0 - braking * t)
        } else {
            (top, 0.0)
        };
        // Within the stiction's creep (1e-5 m) once stopped.
        assert!(
            (row[along] - s).abs() < 1e-4 && (row[speed] - v).abs() < 2e-3,
            "at {t}: the crate at {} moving {}, the closed form {s}, {v}",
            row[along],
            row[speed]
        );
    }
}

/// `defaults units orientation_type` names the sequence of the three
/// turns orientations give: a body sequence turns about the axes the turns
/// before left (`R₁ R₂ R₃`), a space one about ground's (`R₃ R₂ R₁`).
/// Checked by hand (body123 of 90°, 90°, 0° takes the x axis to ground's
/// y), against the dataset's REULER for body313, and by the identity
/// space123(a, b, c) = body321(c, b, a), at angles drawn at random.
#[test]
fn orientations_follow_the_orientation_type() {
    let axes = |orientation_type: &str, angles: [f64; 3]| -> Matrix3<f64> {
        let text = format!(
            "defaults units length = meter angle = deg orientation_type = {orientation_type}
model create model_name = o
marker create marker_name = .o.ground.M adams_id = 7 location = 0, 0, 0 orientation = {}, {}, {}
",
            angles[0], angles[1], angles[2]
        );
        let model = view_model(&text).unwrap_or_else(|errors| panic!("{errors}"));
        let marker = model
            .scene
            .markers
            .iter()
            .find(|marker| marker.id == Some(7))
            .expect("the marker");
        marker.orientation.to_rotation_matrix().into_inner()
    };
    let by_hand = axes("body123", [90.0, 90.0, 0.0]);
    assert!(
        (by_hand.column(0) - Vector3::y()).norm() < 1e-12,
        "{by_hand}"
    );
    let mut seed = 7_u64;
    let mut uniform = |low: f64, high: f64| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        low + (high - low) * (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..10 {
        let [a, b, c] = [0; 3].map(|_| uniform(-180.0, 180.0));
        let dataset = format!(
            "one marker\nPART/1, GROUND\nMARKER/7, PART = 1, REULER = {a}D, {b}D, {c}D\nEND\n"
        );
        let model = super::simulate::model_of(&dataset).unwrap_or_else(|errors| panic!("{errors}"));
        let reuler = model.scene.markers[0]
            .orientation
            .to_rotation_matrix()
            .into_inner();
        assert!((axes("body313", [a, b, c]) - reuler).norm() < 1e-12);
        assert!((axes("space123", [a, b, c]) - axes("body321", [c, b, a])).norm() < 1e-12);
        let turn = |axis: Vector3<f64>, degrees: f64| {
            Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), degrees.to_radians())
                .into_inner()
        };
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        assert!((axes("body123", [a, b, c]) - turn(x, a) * turn(y, b) * turn(z, c)).norm() < 1e-12);
        assert!(
            (axes("space312", [a, b, c]) - turn(y, c) * turn(x, b) * turn(z, a)).norm() < 1e-12
        );
        assert!((axes("body232", [a, b, c]) - turn(y, a) * turn(z, b) * turn(y, c)).norm() < 1e-12);
    }
    let refused = view_model("defaults units orientation_type = body113\n").expect_err("refused");
    assert!(refused.contains("orients by body113"), "{refused}");
}

/// Kinematic measures read by functions become the solver functions they
/// measure: a `pt2pt` measure (of its to point from its from point,
/// components along `coordinate_rframe`, derivatives in `motion_rframe`),
/// a `point` measure (from ground's origin) and `object` measures of a
/// marker and of a part's centre of mass, angular rates in the file's angle
/// unit (degrees here: `RTOD * WZ`, as View writes them). A request reading
/// them moves as the dataset whose request calls DY, VM, ACCX, WM and WZ by
/// hand, and a sensor on a pt2pt measure stops the run where the dataset's
/// does.
#[test]
fn kinematic_measures_read_by_functions_are_their_functions() {
    let view = r#"defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = k
marker create marker_name = .k.ground.PIVOT adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .k.ground.TILTED adams_id = 5 location = 0.3, 0, 0 orientation = 30d, 20d, 0d
part create rigid_body name_and_position part_name = .k.arm adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body initial_velocity part_name = .k.arm wz = 90
marker create marker_name = .k.arm.HUB adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .k.arm.CM adams_id = 3 location = 0.5, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .k.arm.TIP adams_id = 4 location = 1, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .k.arm mass = 2 center_of_mass_marker = .k.arm.CM ixx = 0.01 iyy = 0.2 izz = 0.2
constraint create joint revolute joint_name = .k.HINGE adams_id = 1 i_marker_name = .k.arm.HUB j_marker_name = .k.ground.PIVOT
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9.80665 z_component_gravity = 0
measure create pt2pt measure_name = .k.TIP_HEIGHT from_point = .k.ground.PIVOT to_point = .k.arm.TIP coordinate_rframe = .k.ground.TILTED characteristic = translational_displacement component = y_component create_measure_display = no
measure create pt2pt measure_name = .k.TIP_SPEED from_point = .k.ground.TILTED to_point = .k.arm.TIP motion_rframe = .k.arm.HUB characteristic = translational_velocity component = mag_component
measure create point measure_name = .k.TIP_ACCELERATION point = .k.arm.TIP characteristic = translational_acceleration component = x_component
measure create object measure_name = .k.SPIN from_first = no object = .k.arm.TIP characteristic = angular_velocity component = mag_component
measure create object measure_name = .k.ARM_SPIN from_first = no object = .k.arm coordinate_rframe = .k.ground.TILTED characteristic = cm_angular_velocity component = z_component
measure create object measure_name = .k.HINGE_FORCE object = .k.HINGE characteristic = element_force component = x_component
output_control create request request_name = .k.MEASURED adams_id = 1 comment = measured f2 = ".k.TIP_HEIGHT" f3 = ".k.TIP_SPEED" f4 = ".k.TIP_ACCELERATION" f5 = ".k.SPIN" f6 = "2 * .k.ARM_SPIN"
executive_control create sensor sensor_name = .k.LEVEL adams_id = 1 compare = le value = -0.5 error = 1e-6 codgen = off halt = on print = off restart = off return = off yydump = off function = ".k.TIP_HEIGHT" evaluate = ""
simulation single_run transient end_time = 3 number_of_steps = 30
"#;
    let dataset = "the measured arm, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/5, PART = 1, QP = 0.3, 0, 0, REULER = 30D, 20D, 0D
PART/2, MASS = 2, CM = 3, IP = 0.01, 0.2, 0.2, WZ = 1.5707963267948966
MARKER/2, PART = 2
MARKER/3, PART = 2, QP = 0.5, 0, 0
MARKER/4, PART = 2, QP = 1, 0, 0
JOINT/1, REVOLUTE, I = 2, J = 1
ACCGRAV/JGRAV = -9.80665
REQUEST/1, F2 = DY(4, 1, 5)\\F3 = VM(4, 5, 2)\\F4 = ACCX(4, 0, 0, 0)\\F5 = RTOD * WM(4, 0)\\F6 = 2 * RTOD * WZ(3, 0, 5)
SENSOR/1, LE, VALUE = -0.5, ERROR = 1E-6, HALT, FUNCTION = DY(4, 1, 5)
VARIABLE/1, FUNCTION = DY(4, 1, 5)
VARIABLE/2, FUNCTION = VM(4, 5, 2)
VARIABLE/3, FUNCTION = ACCX(4, 0, 0, 0)
VARIABLE/4, FUNCTION = RTOD * WM(4, 0)
VARIABLE/5, FUNCTION = RTOD * WZ(3, 0, 5)
VARIABLE/6, FUNCTION = JOINT(1, 1, 2, 0)
END
";
    let rows = same_motion(view, dataset, 1e-7);
    // The arm swings, and its tip passes the sensor's level (in the tilted
    // frame): the run halts there.
    let last = rows.last().expect("rows");
    let height = last.len() - 11;
    assert!(
        rows.len() < 31,
        "the sensor halts the run: {} rows",
        rows.len()
    );
    assert!((last[height] + 0.5).abs() < 1e-5, "{last:?}");
    // The measures are VARIABLEs, a column each, as View has the solver
    // compute them (the joint's force too, which no function reads); a
    // part's kinetic energy is left out with a note, and refused where a
    // function reads it.
    let model = view_model(view).expect("the model");
    let notes: Vec<&str> = model.notes.iter().map(|(note, _)| note.as_str()).collect();
    assert!(
        notes
            .iter()
            .any(|note| note.contains("VARIABLE/1 = K.TIP_HEIGHT")
                && note.contains("VARIABLE/6 = K.HINGE_FORCE")),
        "{notes:?}"
    );
    let energy = "measure create object measure_name = .k.ENERGY object = .k.arm characteristic = kinetic_energy component = mag_component\n";
    let unread = view.replace("output_control", &format!("{energy}output_control"));
    let model = view_model(&unread).expect("the model");
    assert!(
        model
            .notes
            .iter()
            .any(|(note, _)| note.starts_with("1 measure mbexpr does not compute")),
        "{:?}",
        model.notes
    );
    let refused = view_model(&unread.replace("f6 = \"2 * .k.ARM_SPIN\"", "f6 = \".k.ENERGY\""))
        .expect_err("a part's kinetic energy is refused");
    assert!(
        refused.contains("a part's characteristic kinetic_energy is not one mbexpr reads"),
        "{refused}"
    );
}

/// Object measures of elements, orientation measures and angle measures
/// become the functions View writes for them (each seen in a View export
/// beside its `.cmd`): a joint's projection angles and rates of one marker
/// from the other (`RTOD * AZ(21,22)` for `from_first = no`, of J from I
/// for `yes`), its reaction and a force's load as their element functions
/// on I (`from_first = yes`, `JOINT(11,0,1,0)`) or J, along
/// `coordinate_rframe`; a motion's load and the kinematics of its joint;
/// orientations of a marker or a part's frame from another frame in any
/// convention; the included angle of three markers. Angles and their rates
/// are in the file's angle unit: degrees, and radians where the file says
/// `angle = rad`.
#[test]
fn object_orientation_and_angle_measures_are_the_functions_view_writes() {
    let view = r#"defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = k
marker create marker_name = .k.ground.PIVOT adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .k.ground.TILTED adams_id = 5 location = 0.3, 0, 0 orientation = 30d, 20d, 0d
marker create marker_name = .k.ground.RAIL adams_id = 6 location = 0, -2, 0 orientation = 0d, 90d, 0d
part create rigid_body name_and_position part_name = .k.arm adams_id = 2 location = 0, 0, 0 orientation = 40d, 0d, 0d
marker create marker_name = .k.arm.HUB adams_id = 2 relative_to = .k.arm location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .k.arm.CM adams_id = 3 relative_to = .k.arm location = 0.5, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .k.arm.TIP adams_id = 4 relative_to = .k.arm location = 1, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .k.arm mass = 2 center_of_mass_marker = .k.arm.CM ixx = 0.01 iyy = 0.2 izz = 0.2
part create rigid_body name_and_position part_name = .k.slider adams_id = 3 location = 0, -2, 0 orientation = 0d, 90d, 0d
marker create marker_name = .k.slider.S adams_id = 7 relative_to = .k.slider location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .k.slider mass = 1.5 center_of_mass_marker = .k.slider.S ixx = 0.1 iyy = 0.1 izz = 0.1
constraint create joint revolute joint_name = .k.HINGE adams_id = 1 i_marker_name = .k.arm.HUB j_marker_name = .k.ground.PIVOT
constraint create joint translational joint_name = .k.SLIDE adams_id = 2 i_marker_name = .k.slider.S j_marker_name = .k.ground.RAIL
constraint create motion_generator motion_name = .k.PUSH adams_id = 1 joint_name = .k.SLIDE type_of_freedom = translational time_derivative = displacement function = "0.2*sin(2*time)"
force create direct single_component_force single_component_force_name = .k.DAMPER adams_id = 2 type_of_freedom = rotational i_marker_name = .k.arm.HUB j_marker_name = .k.ground.PIVOT action_only = off function = "-0.3*WZ(.k.arm.HUB, .k.ground.PIVOT)"
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9.80665 z_component_gravity = 0
measure create object measure_name = .k.ANGLE_NO from_first = no object = .k.HINGE characteristic = ax_ay_az_projection_angles component = z_component
measure create object measure_name = .k.ANGLE_YES from_first = yes object = .k.HINGE characteristic = ax_ay_az_projection_angles component = z_component
measure create object measure_name = .k.RATE from_first = yes object = .k.HINGE characteristic = angular_velocity component = z_component
measure create object measure_name = .k.SPIN_UP from_first = no object = .k.HINGE coordinate_rframe = .k.ground.TILTED characteristic = angular_acceleration component = y_component
measure create object measure_name = .k.PIN_Y from_first = yes object = .k.HINGE characteristic = element_force component = y_component
measure create object measure_name = .k.PIN_J from_first = no object = .k.HINGE coordinate_rframe = .k.ground.TILTED characteristic = element_force component = mag_component
measure create object measure_name = .k.DAMPING from_first = yes object = .k.DAMPER characteristic = element_torque component = z_component
measure create object measure_name = .k.PUSHING from_first = yes object = .k.PUSH characteristic = element_force component = y_component
measure create object measure_name = .k.PUSH_SPEED from_first = no object = .k.PUSH characteristic = translational_velocity component = y_component
measure create object measure_name = .k.SLID from_first = yes object = .k.SLIDE characteristic = translational_displacement component = mag_component
measure create orient measure_name = .k.HEADING to_frame = .k.arm from_frame = .k.ground.TILTED characteristic = body_3_2_1 component = angle_1_component
measure create orient measure_name = .k.TURN from_frame = .k.ground.TILTED to_frame = .k.arm.TIP characteristic = space_1_2_3 component = angle_3_component
measure create orient measure_name = .k.E0 to_frame = .k.arm.TIP characteristic = euler_parameters component = param_1_component
measure create orient measure_name = .k.COSINE to_frame = .k.arm.TIP from_frame = .k.ground.TILTED characteristic = direction_cosines component = mat_2_1_component
measure create orient measure_name = .k.PITCHED to_frame = .k.arm.TIP characteristic = yaw_pitch_roll component = angle_1_component
measure create orient measure_name = .k.PSI to_frame = .k.arm.TIP from_frame = .k.ground characteristic = euler_angles component = angle_1_component
measure create angle measure_name = .k.OPENING first_point = .k.arm.TIP middle_point = .k.ground.PIVOT last_point = .k.ground.TILTED
output_control create request request_name = .k.MEASURED adams_id = 1 f2 = ".k.ANGLE_NO" f3 = "2 * .k.PIN_Y" f4 = ".k.OPENING"
simulation single_run transient end_time = 2 number_of_steps = 20
"#;
    let dataset = "the measured arm and slider, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/5, PART = 1, QP = 0.3, 0, 0, REULER = 30D, 20D, 0D
MARKER/6, PART = 1, QP = 0, -2, 0, REULER = 0D, 90D, 0D
PART/2, MASS = 2, CM = 3, IP = 0.01, 0.2, 0.2, REULER = 40D, 0D, 0D
MARKER/2, PART = 2
MARKER/3, PART = 2, QP = 0.5, 0, 0
MARKER/4, PART = 2, QP = 1, 0, 0
PART/3, MASS = 1.5, CM = 7, IP = 0.1, 0.1, 0.1, QG = 0, -2, 0, REULER = 0D, 90D, 0D
MARKER/7, PART = 3
JOINT/1, REVOLUTE, I = 2, J = 1
JOINT/2, TRANSLATIONAL, I = 7, J = 6
MOTION/1, JOINT = 2, TRANSLATION, DISPLACEMENT, FUNCTION = 0.2*SIN(2*TIME)
SFORCE/2, ROTATION, I = 2, J = 1, FUNCTION = -0.3*WZ(2, 1)
ACCGRAV/JGRAV = -9.80665
REQUEST/1, F2 = RTOD * AZ(2,1)\\F3 = 2 * JOINT(1,0,3,0)\\F4 = RTOD * INCANG(4,1,5)
VARIABLE/1, FUNCTION = RTOD * AZ(2,1)
VARIABLE/2, FUNCTION = RTOD * AZ(1,2)
VARIABLE/3, FUNCTION = RTOD * WZ(1,2,0)
VARIABLE/4, FUNCTION = RTOD * WDTY(2,1,5)
VARIABLE/5, FUNCTION = JOINT(1,0,3,0)
VARIABLE/6, FUNCTION = JOINT(1,1,1,5)
VARIABLE/7, FUNCTION = SFORCE(2,0,8,0)
VARIABLE/8, FUNCTION = MOTION(1,0,3,0)
VARIABLE/9, FUNCTION = VY(7,6,0)
VARIABLE/10, FUNCTION = DM(6,7)
VARIABLE/11, FUNCTION = RTOD * ORIENT(6,1,2,5)
VARIABLE/12, FUNCTION = RTOD * ORIENT(13,3,4,5)
VARIABLE/13, FUNCTION = ORIENT(27,1,4,0)
VARIABLE/14, FUNCTION = ORIENT(29,2,4,5)
VARIABLE/15, FUNCTION = RTOD * YAW(4,0)
VARIABLE/16, FUNCTION = RTOD * PSI(4,0)
VARIABLE/17, FUNCTION = RTOD * INCANG(4,1,5)
END
";
    let rows = same_motion(view, dataset, 1e-7);
    let (exported, _) = simulate::view_dataset_text(view).unwrap_or_else(|_| panic!("read"));
    same_motion(view, &exported, 1e-12);
    // The arm swings (its angle from the pivot, and from the arm the
    // opposite), the slider is pushed: the measures move.
    let last = rows.last().expect("rows");
    let first = &rows[0];
    let variable = |k: usize| last.len() - 17 + k - 1;
    assert!((first[variable(1)] - 40.0).abs() < 1e-9, "{first:?}");
    assert!((last[variable(1)] + last[variable(2)]).abs() < 1e-9);
    assert!((last[variable(1)] - 40.0).abs() > 1.0);
    assert!(last[variable(8)].abs() > 1.0, "the motion pushes: {last:?}");
    assert!((last[variable(16)] - last[variable(1)]).abs() < 1e-9);
    // In radians where the file says so: no RTOD.
    let in_radians = view.replace("angle = deg", "angle = rad");
    same_motion(&in_radians, &dataset.replace("RTOD * ", ""), 1e-7);
    // What a measure cannot be is wrong where a function reads it.
    for (measure, message) in [
        (
            "measure create object measure_name = .k.X object = .k.HINGE characteristic = ax_ay_az_projection_angles component = mag_component",
            "projection angles have no magnitude",
        ),
        (
            "measure create orient measure_name = .k.X to_frame = .k.arm.TIP characteristic = euler_parameters component = angle_1_component",
            "its component angle_1_component is not one of a euler_parameters measure",
        ),
        (
            "measure create orient measure_name = .k.X to_frame = .k.arm.TIP characteristic = body_1_1_2 component = angle_1_component",
            "body_1_1_2 is no sequence of turns mbexpr reads",
        ),
        (
            "measure create angle measure_name = .k.X first_point = .k.arm.TIP middle_point = .k.ground.PIVOT",
            "give its first_point, middle_point and last_point",
        ),
    ] {
        let text = view.replace("output_control", &format!("{measure}\noutput_control"));
        let refused =
            view_model(&text.replace("f4 = \".k.OPENING\"", "f4 = \".k.X\"")).expect_err(measure);
        assert!(refused.contains(message), "{measure}: {refused}");
    }
}

/// A simulation script of solver commands (`solver_commands = "!
/// Insert ACF commands here:", "SIMULATE/STATIC", "SIMULATE/DYNAMIC,
/// END=5.0, DTOUT=1.0E-02"`, as View writes a scripted simulation) gives
/// the run as its command file would: the end, the steps, a static
/// equilibrium first; commands mbexpr does not run leave a note.
#[test]
fn a_scripted_simulations_solver_commands_give_the_run() {
    let model = |commands: &str| {
        let text = format!(
            "model create model_name = s
part create rigid_body name_and_position part_name = .s.ball adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
marker create marker_name = .s.ball.M adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .s.ball mass = 1 center_of_mass_marker = .s.ball.M ixx = 1 iyy = 1 izz = 1
simulation script create sim_script_name = .s.Last_Sim commands = \"simulation single_run scripted sim_script_name=.s.SCRIPT_1 reset_before_and_after=yes model_name=.s\"
simulation script create sim_script_name = .s.SCRIPT_1 solver_commands = {commands}
"
        );
        view_model(&text).unwrap_or_else(|errors| panic!("{errors}"))
    };
    let scripted = model(
        "\"! Insert ACF commands here:\", \"SIMULATE/STATIC\",  &\n   \"SIMULATE/DYNAMIC, END=5.0, DTOUT=1.0E-02\"",
    );
    assert_eq!(scripted.run, Some((5.0, 500)));
    assert!(scripted.statics);
    let dynamic = model("\"sim/dyn, end = 2, steps = 40\"");
    assert_eq!(dynamic.run, Some((2.0, 40)));
    assert!(!dynamic.statics);
    let changed = model("\"deactivate/joint, id = 1\", \"sim/dyn, end = 1, steps = 10\"");
    assert_eq!(changed.run, None);
    assert!(
        changed
            .notes
            .iter()
            .any(|(note, _)| note.contains("DEACTIVATE changes the model")),
        "{:?}",
        changed.notes
    );
}

/// Locations in cylindrical coordinates (`defaults units
/// coordinate_system_type = cylindrical`: `r, θ, z`, θ in the angle unit)
/// place parts, markers and points as their cartesian equivalents do; a
/// solid drawn by points is refused there.
#[test]
fn cylindrical_locations_are_their_cartesian_places() {
    let model = |system: &str, [hub, tip, part]: [&str; 3]| {
        format!(
            "defaults units length = meter angle = deg force = newton mass = kg time = sec
defaults units coordinate_system_type = {system}
model create model_name = c
marker create marker_name = .c.ground.PIVOT adams_id = 1 location = {hub} orientation = 0d, 0d, 0d
part create rigid_body name_and_position part_name = .c.arm adams_id = 2 location = {part} orientation = 20d, 0d, 0d
marker create marker_name = .c.arm.HUB adams_id = 2 location = {hub} orientation = 0d, 0d, 0d
marker create marker_name = .c.arm.TIP adams_id = 3 location = {tip} orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .c.arm mass = 2 center_of_mass_marker = .c.arm.TIP ixx = 0.01 iyy = 0.2 izz = 0.2
constraint create joint revolute joint_name = .c.HINGE adams_id = 1 i_marker_name = .c.arm.HUB j_marker_name = .c.ground.PIVOT
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9.80665 z_component_gravity = 0
simulation single_run transient end_time = 1 number_of_steps = 10
"
        )
    };
    let (sin, cos) = (30.0_f64.to_radians()).sin_cos();
    let (s2, c2) = (120.0_f64.to_radians()).sin_cos();
    let cartesian = model(
        "cartesian",
        [
            &format!("{}, {}, 0.1", 0.5 * cos, 0.5 * sin),
            &format!("{}, {}, 0.1", 1.5 * cos, 1.5 * sin),
            &format!("{}, {}, 0", 0.2 * c2, 0.2 * s2),
        ],
    );
    let cylindrical = model(
        "cylindrical",
        ["0.5, 30, 0.1", "1.5, 30d, 0.1", "0.2, 120, 0"],
    );
    let (exported, _) = simulate::view_dataset_text(&cartesian).unwrap_or_else(|_| panic!("read"));
    let rows = same_motion(&cylindrical, &exported, 1e-12);
    assert!(rows[0] != rows[10], "the arm swings");
    let radians = model(
        "cylindrical",
        [
            "0.5, 0.5235987755982988, 0.1",
            "1.5, 30d, 0.1",
            "0.2, 2.0943951023931953, 0",
        ],
    )
    .replace("angle = deg", "angle = rad");
    same_motion(&radians, &exported, 1e-12);
    let extruded = format!(
        "{cylindrical}geometry create shape extrusion extrusion_name = .c.arm.E reference_marker = .c.arm.TIP points_for_profile = 0, 0, 0, 1, 0, 0, 0, 1, 0 length_along_z_axis = 0.1\n"
    )
    .replace("mass = 2 center_of_mass_marker = .c.arm.TIP ixx = 0.01 iyy = 0.2 izz = 0.2", "density = 100");
    let refused = view_model(&extruded).expect_err("points in cylindrical coordinates");
    assert!(refused.contains("cartesian coordinates only"), "{refused}");
}

/// The measures' VARIABLEs take the ids the file's variables leave free,
/// in order, as View's export numbers them (a user's delta robot:
/// variables 1-4 and 8-18 leave 5, 6, 7 to its first three measures and
/// 19 on to the rest).
#[test]
fn measures_take_the_variable_ids_left_free() {
    let text = "model create model_name = v
part create rigid_body name_and_position part_name = .v.ball adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
marker create marker_name = .v.ball.M adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .v.ball mass = 1 center_of_mass_marker = .v.ball.M ixx = 1 iyy = 1 izz = 1
data_element create variable variable_name = .v.A adams_id = 1 function = \"1\"
data_element create variable variable_name = .v.B adams_id = 2 function = \"2\"
data_element create variable variable_name = .v.C adams_id = 4 function = \"4\"
measure create point measure_name = .v.HEIGHT point = .v.ball.M characteristic = translational_displacement component = y_component
measure create point measure_name = .v.SPEED point = .v.ball.M characteristic = translational_velocity component = y_component
measure create point measure_name = .v.FALL point = .v.ball.M characteristic = translational_acceleration component = y_component
";
    let model = view_model(text).unwrap_or_else(|errors| panic!("{errors}"));
    assert!(
        model.notes.iter().any(|(note, _)| note
            .ends_with("VARIABLE/3 = V.HEIGHT, VARIABLE/5 = V.SPEED, VARIABLE/6 = V.FALL")),
        "{:?}",
        model.notes
    );
}

/// A general constraint (`constraint create general_constraint`, its
/// FUNCTION given by a later `modify`, as View writes it) is the dataset's
/// GCON: a point mass held 2 from ground's origin swings as the dataset's
/// pendulum does; without its `i_marker_name` (as View exports one made
/// without it) it runs alike, its reaction reported at ground's origin.
#[test]
fn a_view_general_constraint_is_the_datasets_gcon() {
    let view = |marker: &str| {
        format!(
            "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = g
marker create marker_name = .g.ground.O adams_id = 1 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body name_and_position part_name = .g.ball adams_id = 2 location = 2, 0, 0 orientation = 0, 0, 0
marker create marker_name = .g.ball.M adams_id = 20 location = 2, 0, 0 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .g.ball mass = 1.5 center_of_mass_marker = .g.ball.M ixx = 0.2 iyy = 0.3 izz = 0.4
constraint create general_constraint general_constraint_name = .g.GCON_1 adams_id = 1{marker}
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9.80665 z_component_gravity = 0
output_control create request request_name = .g.PLACE adams_id = 1 f2 = \"DX(.g.ball.M)\" f3 = \"DY(.g.ball.M)\"
constraint modify general_constraint general_constraint_name = .g.GCON_1 function = \"DM(.g.ball.M, .g.ground.O) - 2\"
simulation single_run transient end_time = 1 number_of_steps = 10
"
        )
    };
    let dataset = "distance
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1.5, CM = 20, IP = 0.2, 0.3, 0.4, QG = 2, 0, 0
MARKER/20, PART = 2
GCON/1, I = 1, FUNCTION = DM(20, 1) - 2
ACCGRAV/JGRAV = -9.80665
REQUEST/1, F2 = DX(20)\\F3 = DY(20)
END
";
    let rows = same_motion(&view(" i_marker_name = .g.ground.O"), dataset, 1e-7);
    assert!(rows[10][rows[10].len() - 1] < -1.0, "the mass swings down");
    same_motion(&view(""), dataset, 1e-7);
}

/// Adams Controls exports a plant's inputs and outputs in models named
/// inside the model (`model create model_name = .PM.Controls_Plant_1`,
/// then `.PM.PM`), and names the ground by its bare name after them: the
/// inner models are namespaces of the outer one, its ground the only one.
#[test]
fn models_named_inside_the_model_are_its_namespaces() {
    let view = "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = g
model create model_name = .g.Controls_Plant_1
model create model_name = .g.g
part modify rigid_body name_and_position part_name = ground adams_id = 1
marker create marker_name = .g.ground.O adams_id = 1 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body name_and_position part_name = .g.ball adams_id = 2 location = 2, 0, 0 orientation = 0, 0, 0
marker create marker_name = .g.ball.M adams_id = 20 location = 2, 0, 0 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .g.ball mass = 1.5 center_of_mass_marker = .g.ball.M ixx = 0.2 iyy = 0.3 izz = 0.4
marker create marker_name = .g.ball.P adams_id = 21 location = 0, 0, 0 orientation = 0, 0, 0
constraint create joint spherical joint_name = .g.PIN adams_id = 1 i_marker_name = .g.ball.P j_marker_name = .g.ground.O
force create body gravitational gravity_field_name = gravity x_component_gravity = 0 y_component_gravity = -9.80665 z_component_gravity = 0
output_control create request request_name = .g.PLACE adams_id = 1 f2 = \"DX(.g.ball.M)\" f3 = \"DY(.g.ball.M)\"
simulation single_run transient end_time = 1 number_of_steps = 10
";
    let dataset = "a ball on a rod
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1.5, CM = 20, IP = 0.2, 0.3, 0.4, QG = 2, 0, 0
MARKER/20, PART = 2
MARKER/21, PART = 2, QP = -2, 0, 0
JOINT/1, SPHERICAL, I = 21, J = 1
ACCGRAV/JGRAV = -9.80665
REQUEST/1, F2 = DX(20)\\F3 = DY(20)
END
";
    let rows = same_motion(view, dataset, 1e-7);
    assert!(rows[10][rows[10].len() - 1] < -1.0, "the ball swings down");
}

/// View writes long point lists with the comma at the start of each
/// continued line (`points_for_profile = 0, 0, 0  &` then `, 1, 0, 0  &`);
/// they read as one list, and a line with a comma but no value is still
/// no statement.
#[test]
fn a_list_continued_with_leading_commas_reads() {
    let text = "model create model_name = e
part create rigid_body name_and_position part_name = .e.wedge adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
marker create marker_name = .e.wedge.M adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .e.wedge mass = 1 center_of_mass_marker = .e.wedge.M ixx = 1 iyy = 1 izz = 1
geometry create shape extrusion  &\r
   extrusion_name = .e.wedge.EXTRUSION_8  &\r
   reference_marker = .e.wedge.M  &\r
   points_for_profile = 0.0, 0.0, -25.0  &\r
      , 866.025, 0.0, -25.0  &\r
      , 0.0, 500.0, -25.0  &\r
      , 0.0, 0.0, -25.0  &\r
   length_along_z_axis = 50.0\r
";
    let model = view_model(text).unwrap_or_else(|errors| panic!("{errors}"));
    assert_eq!(model.scene.bodies.len(), 1);
    let broken = text.replace("      , 0.0, 500.0, -25.0  &\r\n", "      ,  &\r\n");
    let error = view_model(&broken).expect_err("a comma with no value");
    assert!(error.contains("not a View command"), "{error}");
}

/// A View gear (`constraint create complex_joint gear`: two joints and the
/// common-velocity marker at the pitch point) is the dataset's GEAR: a
/// torque on the first of two spur wheels (pitch radii 0.1 and 0.27)
/// turns them as their radii say.
#[test]
fn a_view_gear_is_the_datasets_gear() {
    let view = "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = g
marker create marker_name = .g.ground.A adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.ground.B adams_id = 2 location = 0.37, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.ground.PITCH adams_id = 3 location = 0.1, 0, 0 orientation = 0d, -90d, 0d
part create rigid_body name_and_position part_name = .g.pinion adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.pinion.M adams_id = 20 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .g.pinion mass = 1 center_of_mass_marker = .g.pinion.M ixx = 1 iyy = 1 izz = 0.5
part create rigid_body name_and_position part_name = .g.wheel adams_id = 3 location = 0.37, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .g.wheel.M adams_id = 30 location = 0.37, 0, 0 orientation = 0d, 0d, 0d relative_to = .g.ground
part create rigid_body mass_properties part_name = .g.wheel mass = 1 center_of_mass_marker = .g.wheel.M ixx = 1 iyy = 1 izz = 0.2
constraint create joint revolute joint_name = .g.J1 adams_id = 1 i_marker_name = .g.pinion.M j_marker_name = .g.ground.A
constraint create joint revolute joint_name = .g.J2 adams_id = 2 i_marker_name = .g.wheel.M j_marker_name = .g.ground.B
constraint create complex_joint gear gear_name = .g.GEAR_1 adams_id = 1 joint_name = .g.J1, .g.J2 common_velocity_marker = .g.ground.PITCH
force create direct single_component_force single_component_force_name = .g.TORQUE adams_id = 1 type_of_freedom = rotational action_only = off i_marker_name = .g.pinion.M j_marker_name = .g.ground.A function = \"3.0\"
output_control create request request_name = .g.TURNS adams_id = 1 f1 = \"AZ(.g.pinion.M, .g.ground.A)\" f2 = \"AZ(.g.wheel.M, .g.ground.B)\"
simulation single_run transient end_time = 1 number_of_steps = 10
";
    let dataset = "the spur gears, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0.37, 0, 0
MARKER/3, PART = 1, QP = 0.1, 0, 0, REULER = 0, -90D, 0
PART/2, MASS = 1, CM = 20, IP = 1, 1, 0.5
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 1, 1, 0.2, QG = 0.37, 0, 0
MARKER/30, PART = 3
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, REVOLUTE, I = 30, J = 2
GEAR/1, JOINTS = 1, 2, CV = 3
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = 3.0
REQUEST/1, F1 = AZ(20, 1), F2 = AZ(30, 2)
END
";
    let rows = same_motion(view, dataset, 1e-8);
    // The wheels turn against each other as their radii say.
    let last = rows.last().expect("rows");
    let [pinion, wheel] = [last.len() - 2, last.len() - 1];
    assert!(last[pinion] > 0.1, "{last:?}");
    assert!(
        (last[wheel] + last[pinion] * 0.1 / 0.27).abs() < 1e-6,
        "{last:?}"
    );
}

/// View's plate (`geometry create shape plate`: corners at markers, each
/// a circle of `radius` joined to the next by tangent lines, `width`
/// thick about the corners' plane): without rounding, a rectangle is the
/// block of its sides; a rounded triangle in a tilted plane is the same
/// plate with its outline drawn as 3 000 corners (the arcs as chords); a
/// concave outline is refused.
#[test]
fn a_plates_mass_agrees_with_a_block_and_its_drawn_outline() {
    let density = 7.8;
    let corner = |name: &str, at: Vector3<f64>| {
        format!(
            "marker create marker_name = .s.body.{name} location = {}, {}, {} orientation = 0d, 0d, 0d relative_to = .s.ground\n",
            at.x, at.y, at.z
        )
    };
    let plate = |points: &[Vector3<f64>], width: f64, radius: f64| {
        let mut text = String::new();
        let mut names = Vec::new();
        for (k, point) in points.iter().enumerate() {
            text.push_str(&corner(&format!("C{k}"), *point));
            names.push(format!(".s.body.C{k}"));
        }
        text.push_str(&format!(
            "geometry create shape plate plate_name = .s.body.P marker_name = {} width = {width} radius = {radius}\n",
            names.join(", ")
        ));
        text
    };
    let (a, b, t) = (0.4, 0.25, 0.03);
    let rectangle = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(a, 0.0, 0.0),
        Vector3::new(a, b, 0.0),
        Vector3::new(0.0, b, 0.0),
    ];
    let flat = solid_mass(density, &plate(&rectangle, t, 0.0));
    let block = solid_mass(
        density,
        &format!(
            "{}geometry create shape block block_name = .s.body.B corner_marker = .s.body.K diag_corner_coords = {a}, {b}, {t}",
            corner("K", Vector3::new(0.0, 0.0, -t / 2.0))
        ),
    );
    assert!(
        differs(flat, block, 1.0) < 1e-12,
        "{flat:?} against {block:?}"
    );
    // A triangle in a tilted plane, rounded by 0.05.
    let (e1, e2) = (Vector3::new(0.6, 0.8, 0.0), Vector3::new(-0.48, 0.36, 0.8));
    let place = |[u, v]: [f64; 2]| Vector3::new(0.2, -0.1, 0.3) + e1 * u + e2 * v;
    let triangle = [[0.0, 0.0], [0.5, 0.1], [0.15, 0.4]];
    let radius = 0.05;
    let rounded = solid_mass(density, &plate(&triangle.map(place), t, radius));
    let mut outline = Vec::new();
    for k in 0..3 {
        let [before, at, after] = [triangle[(k + 2) % 3], triangle[k], triangle[(k + 1) % 3]];
        let normal = |p: [f64; 2], q: [f64; 2]| {
            (q[1] - p[1]).atan2(q[0] - p[0]) - std::f64::consts::FRAC_PI_2
        };
        let (from, to) = (normal(before, at), normal(at, after));
        let turn = (to - from).rem_euclid(std::f64::consts::TAU);
        for step in 0..=1000 {
            let angle = from + turn * step as f64 / 1000.0;
            outline.push(place([
                at[0] + radius * angle.cos(),
                at[1] + radius * angle.sin(),
            ]));
        }
    }
    let drawn = solid_mass(density, &plate(&outline, t, 0.0));
    assert!(
        differs(rounded, drawn, 1.0) < 2e-6,
        "{rounded:?} against {drawn:?}"
    );
    let concave = [[0.0, 0.0], [0.5, 0.0], [0.1, 0.1], [0.0, 0.5]].map(place);
    let text = format!(
        "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = s
material create material_name = .s.stuff density = 1
part create rigid_body name_and_position part_name = .s.body adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .s.body material_type = .s.stuff
{}",
        plate(&concave, t, radius)
    );
    let refused = view_model(&text).expect_err("a concave plate");
    assert!(refused.contains("concave outline"), "{refused}");
}

/// View's extrusion (`points_for_profile` in its reference marker, all at
/// one z, extruded along z by `length_along_z_axis`): a rectangle is the
/// block of its sides; a triangle is the plate of its corners (checked
/// against the block above), drawn either way round and extruded either
/// way along z (to 1e-10: the moments about the part's origin, 3.7 from
/// the centre, lose digits moved back to it).
#[test]
fn an_extrusions_mass_agrees_with_a_block_and_a_plate() {
    let density = 2.7;
    let (a, b, length) = (0.3, 0.2, 0.05);
    let extrusion = |points: &[[f64; 2]], z: f64, length: f64| {
        let profile: Vec<String> = points
            .iter()
            .map(|[x, y]| format!("{x}, {y}, {z}"))
            .collect();
        format!(
            "geometry create shape extrusion extrusion_name = .s.body.E reference_marker = .s.body.M1 analytical = yes points_for_profile = {} length_along_z_axis = {length}",
            profile.join(", ")
        )
    };
    let rectangle = [[0.0, 0.0], [a, 0.0], [a, b], [0.0, b], [0.0, 0.0]];
    let block = solid_mass(
        density,
        &format!(
            "geometry create shape block block_name = .s.body.B corner_marker = .s.body.M1 diag_corner_coords = {a}, {b}, {length}"
        ),
    );
    let extruded = solid_mass(density, &extrusion(&rectangle, 0.0, length));
    assert!(
        differs(extruded, block, 1.0) < 1e-10,
        "{extruded:?} against {block:?}"
    );
    let backwards = solid_mass(density, &extrusion(&rectangle, length, -length));
    assert!(
        differs(backwards, block, 1.0) < 1e-10,
        "{backwards:?} against {block:?}"
    );
    let triangle = [[0.0, 0.0], [a, 0.05], [0.1, b]];
    let plate = solid_mass(
        density,
        &format!(
            "marker create marker_name = .s.body.C0 location = 0, 0, 0 orientation = 0d, 0d, 0d relative_to = .s.body.M1
marker create marker_name = .s.body.C1 location = {a}, 0.05, 0 orientation = 0d, 0d, 0d relative_to = .s.body.M1
marker create marker_name = .s.body.C2 location = 0.1, {b}, 0 orientation = 0d, 0d, 0d relative_to = .s.body.M1
geometry create shape plate plate_name = .s.body.P marker_name = .s.body.C0, .s.body.C1, .s.body.C2 width = {length} radius = 0"
        ),
    );
    let mut clockwise = triangle;
    clockwise.reverse();
    for (points, z, along) in [
        (triangle, -length / 2.0, length),
        (clockwise, length / 2.0, -length),
    ] {
        let extruded = solid_mass(density, &extrusion(&points, z, along));
        assert!(
            differs(extruded, plate, 1.0) < 1e-10,
            "{extruded:?} against {plate:?}"
        );
    }
}

/// A feature of a solid (`geometry create feature blend`, a hole, a
/// chamfer) changes its volume: where the part's mass comes from its
/// solids it is refused at its place; where the file gives the mass it
/// only draws, and the model reads.
#[test]
fn a_solids_feature_is_refused_where_the_mass_comes_from_the_solid() {
    let text = |mass: &str| {
        format!(
            "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = f
material create material_name = .f.steel density = 7801
part create rigid_body name_and_position part_name = .f.plate adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
marker create marker_name = .f.plate.CORNER adams_id = 2 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create rigid_body mass_properties part_name = .f.plate {mass}
geometry create shape block block_name = .f.plate.BOX_9 corner_marker = .f.plate.CORNER diag_corner_coords = 0.25, 0.02, 0.25
geometry create feature blend blend_name = .f.plate.BOX_9.BLEND_1 subtype = edge radius1 = 0.05 radius2 = 0.05 reference_marker = .f.plate.CORNER locations = 0.0, 0.0, 0.125 chamfer = no
geometry modify feature blend blend_name = .f.plate.BOX_9.BLEND_1 radius1 = 0.04
"
        )
    };
    let refused = view_model(&text("material_type = .f.steel")).expect_err("refused");
    assert!(
        refused.contains("8:1: ") && refused.contains("changes its solid's volume"),
        "{refused}"
    );
    assert_eq!(
        refused.matches("changes its solid's volume").count(),
        1,
        "{refused}"
    );
    let given = text("mass = 3 center_of_mass_marker = .f.plate.CORNER ixx = 1 iyy = 1 izz = 1");
    let model = view_model(&given).unwrap_or_else(|errors| panic!("{errors}"));
    assert_eq!(model.masses[0].mass, 3.0);
}

/// A measure's ends may be points (`point create`), not markers: a
/// marker is made at each point a measure reads. An arm turning freely at
/// 2 rad/s about ground's z carries a point 0.7 out; its distance from a
/// ground point 1.5 along x is `|0.7 (cos 2t, sin 2t) − (1.5, 0)|`.
#[test]
fn a_measure_between_points_follows_them() {
    let text = "defaults units length = meter angle = rad force = newton mass = kg time = sec
model create model_name = p
marker create marker_name = .p.ground.PIVOT adams_id = 1 location = 0, 0, 0 orientation = 0, 0, 0
point create point_name = .p.ground.POST location = 1.5, 0, 0
part create rigid_body name_and_position part_name = .p.arm adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
part create rigid_body initial_velocity part_name = .p.arm wz = 2
marker create marker_name = .p.arm.HUB adams_id = 2 location = 0, 0, 0 orientation = 0, 0, 0
point create point_name = .p.arm.TIP location = 0.5, 0, 0
point modify point_name = .p.arm.TIP location = 0.7, 0, 0
part create rigid_body mass_properties part_name = .p.arm mass = 1 center_of_mass_marker = .p.arm.HUB ixx = 1 iyy = 1 izz = 1
constraint create joint revolute joint_name = .p.HINGE adams_id = 1 i_marker_name = .p.arm.HUB j_marker_name = .p.ground.PIVOT
measure create pt2pt measure_name = .p.GAP from_point = .p.ground.POST to_point = .p.arm.TIP characteristic = translational_displacement component = mag_component
simulation single_run transient end_time = 2 number_of_steps = 20
";
    let model = view_model(text).unwrap_or_else(|errors| panic!("{errors}"));
    let gap = column(&model, "VARIABLE/1");
    for row in rows(&model, 2.0, 20) {
        let t = row[0];
        let expected =
            ((0.7 * (2.0 * t).cos() - 1.5).powi(2) + (0.7 * (2.0 * t).sin()).powi(2)).sqrt();
        assert!(
            (row[gap] - expected).abs() < 1e-7,
            "at {t}: {} against {expected}",
            row[gap]
        );
    }
}

/// View's library springs (`ude create instance` of `.MDI.Forces.spring`
/// and `.MDI.Forces.torsion_spring`, their values set on the instance's
/// variables, some with their units) are the SFORCEs and VARIABLEs View
/// exports for them: `- k*(DM(i,j) - L0) - c*VR(i,j) + preload` with the
/// design length, `- k*(AZ(i,j) - θ0) - c*WZ(i,j,j) + preload` with the
/// design angle, in a millimetre and degree model.
#[test]
fn view_library_springs_are_the_sforces_view_exports() {
    let spring = |instance: &str, values: &[(&str, &str)]| {
        let mut text = format!(
            "ude create instance instance_name = .m.{instance} definition_name = .MDI.Forces.{} location = 0, 0, 0 orientation = 0, 0, 0\n",
            if instance.starts_with("TORSION") {
                "torsion_spring"
            } else {
                "spring"
            }
        );
        for (variable, value) in values {
            text += &format!("variable modify variable_name = .m.{instance}.{variable} {value}\n");
        }
        text + &format!("ude modify instance instance_name = .m.{instance}\n")
    };
    let view = |stiffness_mode: &str| {
        format!(
            "defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = m
marker create marker_name = .m.ground.O adams_id = 1 location = 0, 0, 0 orientation = 0, 0, 0
marker create marker_name = .m.ground.G adams_id = 2 location = 0, 0, 100 orientation = 0, 0, 0
marker create marker_name = .m.ground.W0 adams_id = 3 location = 0, 300, 0 orientation = 30d, 0, 0
part create rigid_body name_and_position part_name = .m.slider adams_id = 2 location = 0, 0, 100 orientation = 0, 0, 0
marker create marker_name = .m.slider.S adams_id = 4 location = 0, 0, 100 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .m.slider mass = 2 center_of_mass_marker = .m.slider.S ixx = 1 iyy = 1 izz = 1
part create rigid_body initial_velocity part_name = .m.slider vz = 50
part create rigid_body name_and_position part_name = .m.wheel adams_id = 3 location = 0, 300, 0 orientation = 0, 0, 0
marker create marker_name = .m.wheel.W1 adams_id = 5 location = 0, 300, 0 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .m.wheel mass = 1 center_of_mass_marker = .m.wheel.W1 ixx = 300 iyy = 300 izz = 500
part create rigid_body initial_velocity part_name = .m.wheel wz = 90
constraint create joint translational joint_name = .m.RAIL adams_id = 1 i_marker_name = .m.slider.S j_marker_name = .m.ground.G
constraint create joint revolute joint_name = .m.PIN adams_id = 2 i_marker_name = .m.wheel.W1 j_marker_name = .m.ground.W0
{}{}simulation single_run transient end_time = 0.5 number_of_steps = 10
",
            spring(
                "SPRING_1",
                &[
                    ("i_marker", "object_value = (.m.slider.S)"),
                    ("j_marker", "object_value = (.m.ground.O)"),
                    ("stiffness_mode", "string_value = \"linear\""),
                    ("stiffness_coefficient", "real_value = 2.0"),
                    ("damping_mode", "string_value = \"linear\""),
                    ("damping_coefficient", "real_value = (0.5(newton-sec/mm))"),
                    ("free_length_mode", "string_value = \"Design_Length\""),
                    ("free_length", "real_value = 1.0"),
                    ("preload", "real_value = 3.0"),
                ]
            ),
            spring(
                "TORSION_SPRING_1",
                &[
                    ("i_marker", "object_value = (.m.ground.W0)"),
                    ("j_marker", "object_value = (.m.wheel.W1)"),
                    ("stiffness_mode", &format!("string_value = \"{stiffness_mode}\"")),
                    ("stiffness_coefficient", "real_value = (10(newton-mm/deg))"),
                    ("damping_mode", "string_value = \"linear\""),
                    ("damping_coefficient", "real_value = 0.2"),
                    ("free_angle_mode", "string_value = \"Design_Angle\""),
                    ("free_angle", "real_value = 1.0"),
                    ("preload", "real_value = 0.0"),
                ]
            ),
        )
    };
    let dataset = "two springs
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = MILLIMETER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0, 0, 100
MARKER/3, PART = 1, QP = 0, 300, 0, REULER = 30D, 0, 0
PART/2, MASS = 2, CM = 4, IP = 1, 1, 1, QG = 0, 0, 100, VZ = 50
MARKER/4, PART = 2
PART/3, MASS = 1, CM = 5, IP = 300, 300, 500, QG = 0, 300, 0, WZ = 1.5707963267948966
MARKER/5, PART = 3
JOINT/1, TRANSLATIONAL, I = 4, J = 2
JOINT/2, REVOLUTE, I = 5, J = 3
SFORCE/1, TRANSLATION, I = 4, J = 1, FUNCTION = - 2*(DM(4,1) - 100) - 0.5*VR(4,1) + 3
SFORCE/2, ROTATION, I = 3, J = 5
, FUNCTION = - 10*180/PI*(AZ(3,5) - PI/6) - 0.2*180/PI*WZ(3,5,5) + 0
VARIABLE/1, FUNCTION = DM(4,1) - 100
VARIABLE/2, FUNCTION = VR(4,1)
VARIABLE/3, FUNCTION = (DX(4,1)*FX(4,1) + DY(4,1)*FY(4,1) + DZ(4,1)*FZ(4,1))/DM(4,1)
VARIABLE/4, FUNCTION = AZ(3,5) - PI/6
VARIABLE/5, FUNCTION = WZ(3,5,5)
VARIABLE/6, FUNCTION = SFORCE(2, 0, 8, 5)
END
";
    let rows = same_motion(&view("linear"), dataset, 1e-7);
    // Both springs act: the slider is pushed back and the wheel slowed.
    let model = view_model(&view("linear")).unwrap_or_else(|errors| panic!("{errors}"));
    let force = column(&model, "VARIABLE/3");
    assert!(rows.iter().any(|row| row[force].abs() > 10.0));
    // A spline's stiffness is refused at the variable that asks for it.
    let error = view_model(&view("spline")).expect_err("a spline is refused");
    assert!(
        error.contains("TORSION_SPRING_1 sets stiffness_mode to SPLINE"),
        "{error}"
    );
}

/// A place computed from numbers at the doubles' limit overflows: the
/// reading stops at the command it comes from, and never writes a
/// non-finite number into the dataset (`simulate --dataset` included).
#[test]
fn places_beyond_the_doubles_range_are_wrong_at_their_command() {
    let text = "part create rigid_body name_and_position part_name = .m.p adams_id = 2 location = 0, 0, 1e308 orientation = 0, 0, 0
marker create marker_name = .m.p.M adams_id = 3 location = 0, 0, -1e308 orientation = 0, 0, 0
part create rigid_body mass_properties part_name = .m.p mass = 1 center_of_mass_marker = .m.p.M ixx = 1 iyy = 1 izz = 1";
    let error = check(text);
    assert!(
        error.starts_with("3:1: MARKER/3 QP computes to NaN") && error.contains("doubles' limit"),
        "{error}"
    );
    let model = format!("model create model_name = m\n{text}\n");
    assert!(simulate::view_dataset_text(&model).is_err());
}

/// View's point mass (`part create point_mass`, its mass, centre-of-mass
/// marker and initial velocity given by the commands of the same name) is
/// the dataset's POINT_MASS: hung on a spring and set swinging, it
/// moves as the dataset written by hand, and
/// straight down it bobs as the closed form says.
#[test]
fn a_view_point_mass_is_the_datasets_point_mass() {
    let view = |velocity: f64| {
        format!(
            "defaults units length = meter angle = deg force = newton mass = kg time = sec
model create model_name = p
marker create marker_name = .p.ground.anchor adams_id = 1 location = 0, 0, 0 orientation = 0d, 0d, 0d
part create point_mass name_and_position point_mass_name = .p.bob adams_id = 2 location = 0, -1, 0 orientation = 0d, 0d, 0d
marker create marker_name = .p.bob.cm adams_id = 3 location = 0, 0, 0 orientation = 0d, 0d, 0d relative_to = .p.bob
part modify point_mass mass_properties point_mass_name = .p.bob mass = 2.0 center_of_mass_marker = .p.bob.cm
part create point_mass initial_velocity point_mass_name = .p.bob vx = {velocity}
force create element_like translational_spring_damper spring_damper_name = .p.spring i_marker_name = .p.bob.cm j_marker_name = .p.ground.anchor stiffness = 100.0 damping = 0.0 displacement_at_preload = 1.0
force create body gravitational gravity_field_name = gravity x_component_gravity = 0.0 y_component_gravity = -9.80665 z_component_gravity = 0.0
simulation single_run transient end_time = 1 number_of_steps = 20
"
        )
    };
    let dataset = "the bob on its spring, by hand
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
POINT_MASS/2, QG = 0, -1, 0, MASS = 2.0, CM = 3, VX = 0.8
MARKER/3, POINT_MASS = 2
SPRINGDAMPER/1, TRANSLATION, I = 3, J = 1, K = 100.0, C = 0.0, LENGTH = 1.0
ACCGRAV/JGRAV = -9.80665
END
";
    same_motion(&view(0.8), dataset, 1e-8);
    // Straight down: y = -1 - g m/k (1 - cos ωt), ω² = k/m.
    let model = view_model(&view(0.0)).unwrap_or_else(|errors| panic!("{errors}"));
    let y = column(&model, "POINT_MASS/2.y");
    let (sag, omega) = (9.80665 * 2.0 / 100.0, (100.0_f64 / 2.0).sqrt());
    for row in rows(&model, 1.0, 20) {
        let exact = -1.0 - sag * (1.0 - (omega * row[0]).cos());
        assert!((row[y] - exact).abs() < 1e-8, "{row:?} against {exact}");
    }
}

/// The value View's language gives `expression`, as the reading puts it in
/// a parameter (the text as written where it is not evaluated), with the
/// variables `n` (4) and `.m.s` ("ab") set before.
fn evaluated(expression: &str) -> String {
    let text = format!(
        "variable set variable_name = n real_value = 4\nvariable set variable_name = .m.s string_value = \"ab\"\nmarker create marker_name = .m.ground.A location = {expression}\n"
    );
    let dataset = mbexpr::model::read(&text, FileKind::Cmd);
    let marker = dataset.statements.last().expect("the marker command");
    match &marker.arguments.last().expect("its location").value {
        mbexpr::model::Value::List(items) => items[0].text.to_string(),
        other => format!("{other:?}"),
    }
}

#[test]
fn view_expressions_evaluate_as_view_does() {
    let cases = [
        "(1 + 2*3)",
        "(2**3**2)",
        "(-2**2)",
        "(7/2)",
        "(RTOI(7/2))",
        "(NINT(-2.5))",
        "(MOD(-7, 3))",
        "(n * 2.5)",
        "(eval(.m.s // \"_\" // RTOI(n)))",
        "(\"x\" // 1.5)",
        "(n > 3 && n < 5)",
        "(!(n == 4) || 0)",
        "(eval(\"2 + 2\"))",
        "(PI * RTOD)",
        "(MAX(1, n, 3) + MIN(2, -1))",
        "(STOI(\"12\") + 1)",
        "(1.5e3 + .5)",
        "(SQRT(-1))",
        "(1/0)",
        "(20g)",
        "(30d)",
        "(LOC_RELATIVE_TO({0, 0, 0}, .m.ground.A))",
        "(unknown + 1)",
        "((1 + 2)",
    ];
    let report: String = cases
        .iter()
        .map(|case| format!("{case} => {}\n", evaluated(case)))
        .collect();
    insta::assert_snapshot!(report);
}

/// The rows of the View file `text` run to `end` with `steps` steps.
fn view_rows(text: &str, end: f64, steps: usize) -> (Vec<String>, Vec<Vec<f64>>) {
    let model = view_model(text).unwrap_or_else(|errors| panic!("{errors}"));
    (simulate::columns(&model), rows(&model, end, steps))
}

/// A chain of links built in a `for` loop (its length a variable, each
/// link's name joined with `//` and `RTOI`, the first pinned to ground in
/// an `if` branch and the others to the link before in the `else`, a
/// `while` loop adding a damper a link) moves as the same chain written
/// out command by command.
#[test]
fn a_chain_built_in_loops_is_the_chain_written_out() {
    let head = "defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = chain
marker create marker_name = .chain.ground.top location = 0, 0, 0 orientation = 0d, 0d, 0d
force create body gravitational gravity_field_name = .chain.gravity x_component_gravity = 0 y_component_gravity = -9806.65 z_component_gravity = 0
";
    let link = |i: usize| {
        let y = -(i as f64 - 1.0) * 100.0;
        let pin = if i == 1 {
            "constraint create joint revolute joint_name = .chain.pin_1 i_marker_name = .chain.link_1.top j_marker_name = .chain.ground.top\n".to_string()
        } else {
            format!(
                "constraint create joint revolute joint_name = .chain.pin_{i} i_marker_name = .chain.link_{i}.top j_marker_name = .chain.link_{}.bottom\n",
                i - 1
            )
        };
        format!(
            "part create rigid_body name_and_position part_name = .chain.link_{i} location = {}, {y}, 0 orientation = 0d, 0d, 0d
part modify rigid_body mass_properties part_name = .chain.link_{i} mass = 0.5 ixx = 417 iyy = 417 izz = 417
marker create marker_name = .chain.link_{i}.top location = 0, {y}, 0 orientation = 0d, 0d, 0d
marker create marker_name = .chain.link_{i}.bottom location = 0, {}, 0 orientation = 0d, 0d, 0d
{pin}",
            10.0 * i as f64,
            y - 100.0
        )
    };
    let damper = |i: usize| {
        format!(
            "force create direct single_component_force single_component_force_name = .chain.damper_{i} type_of_freedom = rotational action_only = off i_marker_name = .chain.link_{i}.top j_marker_name = .chain.link_{i}.bottom function = \"-50*WZ(.chain.link_1.top)\"\n"
        )
    };
    let mut written = head.to_string();
    for i in 1..=3 {
        written.push_str(&link(i));
    }
    for i in 1..=3 {
        written.push_str(&damper(i));
    }
    let looped = format!(
        "{head}variable set variable_name = .chain.links integer_value = 3
variable set variable_name = .chain.length real_value = 100.0
for variable_name = i start_value = 1 end_value = (eval(.chain.links))
  part create rigid_body name_and_position part_name = (eval(\".chain.link_\" // RTOI(i))) &
    location = (10*i), (-(i - 1) * eval(.chain.length)), 0 orientation = 0d, 0d, 0d
  part modify rigid_body mass_properties part_name = (eval(\".chain.link_\" // RTOI(i))) mass = 0.5 &
    ixx = (NINT(0.5 * .chain.length**2 / 12)) iyy = 417 izz = 417
  marker create marker_name = (eval(\".chain.link_\" // RTOI(i) // \".top\")) &
    location = 0, (-(i - 1) * .chain.length), 0 orientation = 0d, 0d, 0d
  marker create marker_name = (eval(\".chain.link_\" // RTOI(i) // \".bottom\")) &
    location = 0, (-i * .chain.length), 0 orientation = 0d, 0d, 0d
  if condition = (i == 1)
    constraint create joint revolute joint_name = .chain.pin_1 i_marker_name = .chain.link_1.top j_marker_name = .chain.ground.top
  else
    constraint create joint revolute joint_name = (eval(\".chain.pin_\" // RTOI(i))) &
      i_marker_name = (eval(\".chain.link_\" // RTOI(i) // \".top\")) &
      j_marker_name = (eval(\".chain.link_\" // RTOI(i - 1) // \".bottom\"))
  end
end ! the links
variable set variable_name = k integer_value = 1
while condition = (k <= .chain.links)
  force create direct single_component_force single_component_force_name = (eval(\".chain.damper_\" // RTOI(k))) &
    type_of_freedom = rotational action_only = off &
    i_marker_name = (eval(\".chain.link_\" // RTOI(k) // \".top\")) &
    j_marker_name = (eval(\".chain.link_\" // RTOI(k) // \".bottom\")) &
    function = \"-150/.chain.links*WZ(.chain.link_1.top)\"
  variable set variable_name = k integer_value = (k + 1)
end
"
    );
    // A function is a string of the solver's language, not evaluated: the
    // looped dampers all read link 1's turn, as the written ones do, and
    // the integer variable `.chain.links` (3) as a design variable.
    let (columns, a) = view_rows(&written, 0.5, 10);
    let (looped_columns, b) = view_rows(&looped, 0.5, 10);
    assert_eq!(columns, looped_columns);
    assert_eq!(columns.len(), 1 + 3 * 13, "{columns:?}");
    for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
        assert!((x - y).abs() <= 1e-9 * y.abs().max(1.0), "{x} against {y}");
    }
    // The chain swings: the last link has moved.
    let last = b.last().expect("rows");
    assert!((last[1 + 2 * 13] - 30.0).abs() > 1.0, "{last:?}");
}

#[test]
fn a_loop_that_cannot_be_carried_out_is_refused_at_its_place() {
    let deep = format!(
        "{}marker create marker_name = .m.ground.A\n{}",
        "for variable_name = i start_value = 1 end_value = 1\n".repeat(70),
        "end\n".repeat(70)
    );
    let cases = [
        "for variable_name = i start_value = 1 end_value = (db_count(.m, \"part\"))\nmarker create marker_name = .m.ground.A\nend".to_string(),
        "for variable_name = i start_value = 1 end_value = 1e7\nmarker create marker_name = .m.ground.A\nend".to_string(),
        "for variable_name = i start_value = 1 end_value = 3 increment_value = 0\nend".to_string(),
        "while condition = (1)\nmarker create marker_name = .m.ground.A\nend".to_string(),
        deep,
        // A `break` outside any loop.
        "if condition = (1)\nbreak\nend".to_string(),
        // 300 000 rounds that write nothing are carried out; writing a
        // command each, they stop at the commands' bound.
        "for variable_name = i start_value = 1 end_value = 300000\nif condition = (i == 300000)\nmarker create marker_name = .m.ground.A location = (i / 100000), 0, 0\nend\nend".to_string(),
        "for variable_name = i start_value = 1 end_value = 300000\nmarker create marker_name = .m.ground.A\nend".to_string(),
        // Loops inside loops that write nothing: bounded by their rounds.
        "for variable_name = i start_value = 1 end_value = 200000\nfor variable_name = j start_value = 1 end_value = 200000\nend\nend".to_string(),
        // A string doubled in a loop: past 64 KiB it is not evaluated, and
        // the location that reads it is refused.
        "variable set variable_name = s string_value = \"ab\"\nfor variable_name = i start_value = 1 end_value = 100\nvariable set variable_name = s string_value = (s // s)\nend\nmarker create marker_name = .m.ground.A location = (STOR(s)), 0, 0".to_string(),
        // Ten thousand `if` blocks inside one another: an error, not a
        // stack overflow.
        format!("{}{}", "if condition = (1)\n".repeat(10_000), "end\n".repeat(10_000)),
    ];
    let report: String = cases
        .iter()
        .map(|case| {
            format!(
                "{}\n  => {}\n",
                case.lines().next().unwrap_or_default(),
                check(case)
            )
        })
        .collect();
    insta::assert_snapshot!(report);
}

/// The commands View carries out for `text`: each command's words and
/// its parameters' values, one a line.
fn carried_out(text: &str) -> String {
    let dataset = mbexpr::model::read(text, FileKind::Cmd);
    let mut lines = String::new();
    for statement in &dataset.statements {
        lines.push_str(&statement.name.to_ascii_lowercase());
        for argument in &statement.arguments {
            if let mbexpr::model::Value::List(items) = &argument.value {
                let values: Vec<&str> = items.iter().map(|item| item.text.as_str()).collect();
                lines.push_str(&format!(
                    " {}={}",
                    argument.keyword.to_ascii_lowercase(),
                    values.join(",")
                ));
            }
        }
        lines.push('\n');
    }
    lines
}

#[test]
fn loops_and_if_blocks_are_carried_out_as_view_does() {
    let cases = [
        // A while loop counting with a variable it sets.
        "variable set variable_name = k real_value = 0\nwhile condition = (k < 3)\nvariable set variable_name = k real_value = (k + 1)\nend\nmarker create marker_name = .m.ground.A location = (k), 0, 0",
        // A break, a continue, a loop counting down by a half.
        "for variable_name = i start_value = 1 end_value = 5\nif condition = (i == 2)\ncontinue\nelseif condition = (i == 4)\nbreak\nend\nmarker create marker_name = (eval(\".m.ground.M\" // RTOI(i)))\nend\nfor variable_name = x start_value = 1 end_value = 0 increment_value = -0.5\nmarker create marker_name = .m.ground.X location = (x), 0, 0\nend",
        // A loop over names; a loop that runs no time.
        "for variable_name = part object_names = .m.A, .m.B\npart create rigid_body name_and_position part_name = (part)\nend\nfor variable_name = i start_value = 2 end_value = 1\nmarker create marker_name = .m.ground.NEVER\nend",
        // A `break` outside any loop, in an `if`: nothing is left out.
        "if condition = (1)\nbreak\nend\nmarker create marker_name = .m.ground.AFTER",
        // An if that reads the model: every branch as written.
        "if condition = (! db_exists(\".colors.RED\"))\ncolor create color_name = .colors.RED\nelse\ncolor modify color_name = .colors.RED\nend",
    ];
    let report: String = cases
        .iter()
        .map(|case| format!("{case}\n  =>\n{}", carried_out(case)))
        .collect();
    insta::assert_snapshot!(report);
}

/// The four-bar linkage of the examples typed as View users type it, each
/// command word and parameter cut short (`part cre rig name`, `loc =`,
/// `color create` for View's `colors create`, a run's `sim single trans`
/// in its script): View reads any beginning that is one name's alone, and
/// so does mbexpr. The same solver dataset as the file written out; a
/// beginning that is more than one name's is refused, both named.
#[test]
fn abbreviated_commands_are_read_as_view_reads_them() {
    let typed = r#"default units len = mm ang = deg force = newton mass = kg ti = sec
default units coord = cartesian orientation_t = body313
mod cre model = four_bar
color create color_name = .four_bar.BRIGHT red = 1 green = 1 blue = 0
mat cre material_name = .four_bar.steel adams = 1 dens = 7.801E-06 young = 2.07E+05 poisson = 0.29
mar cre mar = .four_bar.ground.PIVOT_A adams = 1 loc = 0.0, 0.0, 0.0 ori = 0.0d, 0.0d, 0.0d
mar cre mar = .four_bar.ground.PIVOT_D adams = 2 loc = 400.0, 0.0, 0.0 ori = 0.0d, 0.0d, 0.0d
part cre rig name part_name = .four_bar.crank adams = 2 loc = 0, 0, 0 ori = 0d, 0d, 0d
mar cre mar = .four_bar.crank.END_A adams = 11 loc = 0, 0, 0 ori = 0d, 0d, 0d
mar cre mar = .four_bar.crank.END_B adams = 12 loc = 0, 100, 0 ori = 0d, 0d, 0d
part cre rig mass part_name = .four_bar.crank material = .four_bar.steel
geom cre sha link link_name = .four_bar.crank.LINK_2 i_m = .four_bar.crank.END_A j_m = .four_bar.crank.END_B wid = 20.0 dep = 10.0
part cre rig name part_name = .four_bar.coupler adams = 3 loc = 0, 0, 0 ori = 0d, 0d, 0d
mar cre mar = .four_bar.coupler.END_B adams = 21 loc = 0, 100, 0 ori = 0d, 0d, 0d
mar cre mar = .four_bar.coupler.END_C adams = 22 loc = 300, 250, 0 ori = 0d, 0d, 0d
part cre rig mass part_name = .four_bar.coupler material = .four_bar.steel
geom cre sha link link_name = .four_bar.coupler.LINK_3 i_m = .four_bar.coupler.END_B j_m = .four_bar.coupler.END_C wid = 20.0 dep = 10.0
part cre rig name part_name = .four_bar.rocker adams = 4 loc = 0, 0, 0 ori = 0d, 0d, 0d
mar cre mar = .four_bar.rocker.END_C adams = 31 loc = 300, 250, 0 ori = 0d, 0d, 0d
mar cre mar = .four_bar.rocker.END_D adams = 32 loc = 400, 0, 0 ori = 0d, 0d, 0d
part cre rig mass part_name = .four_bar.rocker material = .four_bar.steel
geom cre sha link link_name = .four_bar.rocker.LINK_4 i_m = .four_bar.rocker.END_C j_m = .four_bar.rocker.END_D wid = 20.0 dep = 10.0
cons cre joint rev joint_name = .four_bar.JOINT_A adams = 1 i_marker = .four_bar.crank.END_A j_marker = .four_bar.ground.PIVOT_A
cons cre joint rev joint_name = .four_bar.JOINT_B adams = 2 i_marker = .four_bar.coupler.END_B j_marker = .four_bar.crank.END_B
cons cre joint rev joint_name = .four_bar.JOINT_C adams = 3 i_marker = .four_bar.rocker.END_C j_marker = .four_bar.coupler.END_C
cons cre joint rev joint_name = .four_bar.JOINT_D adams = 4 i_marker = .four_bar.rocker.END_D j_marker = .four_bar.ground.PIVOT_D
cons cre motion motion_name = .four_bar.MOTION_1 adams = 1 type_of = rotational joint_name = .four_bar.JOINT_A time_der = displacement fun = "360d * time"
force cre body grav gravity_field_name = gravity x_comp = 0.0 y_comp = -9806.65 z_comp = 0.0
output cre req request_name = .four_bar.DRIVE adams = 1 f2 = "AZ(.four_bar.rocker.END_D, .four_bar.ground.PIVOT_D) * RTOD" f3 = "MOTION(.four_bar.MOTION_1, 0, 8, 0)" f4 = "JOINT(.four_bar.JOINT_D, 0, 2, 0)"
sim script cre sim_script_name = .four_bar.Last_Sim commands = "sim single trans type=auto_select initial=no end=1.0 number=20 model_name=.four_bar"
"#;
    let written = include_str!("../examples/simulate/n_view_four_bar.cmd");
    let (full, _) = simulate::view_dataset_text(written).unwrap_or_else(|_| panic!("read"));
    let (short, _) = simulate::view_dataset_text(typed).unwrap_or_else(|unread| match unread {
        simulate::Unread::Refused(errors) => panic!("{}", render(typed, None, &errors)),
        simulate::Unread::Unchecked(problems) => panic!("{problems:?}"),
    });
    assert_eq!(short, full);
    // The command language's own commands cut short as users type them
    // (`var set var = n int = 3`, `for var = i start = 1 end = (n)`,
    // `if cond = ...`): the same dataset as the script written out.
    let loop_typed = r#"default units len = mm ang = deg force = newton mass = kg ti = sec
mod cre model = chain
var set var = n int = 3
var set var = pre string = ".chain.link_"
mar cre mar = .chain.ground.top loc = 0, 0, 0
for var = i start = 1 end = (n)
  part cre rig name part = (eval(pre // RTOI(i))) loc = 0, (-(i - 1) * 100), 0
  part mod rig mass part = (eval(pre // RTOI(i))) mass = 0.5 ixx = 417 iyy = 417 izz = 417
  mar cre mar = (eval(pre // RTOI(i) // ".top")) loc = 0, (-(i - 1) * 100), 0
  mar cre mar = (eval(pre // RTOI(i) // ".bottom")) loc = 0, (-i * 100), 0
  if cond = (i == 1)
    cons cre joint rev joint = .chain.pin_1 i_marker = .chain.link_1.top j_marker = .chain.ground.top
  else
    cons cre joint rev joint = (eval(".chain.pin_" // RTOI(i))) i_marker = (eval(pre // RTOI(i) // ".top")) j_marker = (eval(pre // RTOI(i - 1) // ".bottom"))
  end
end
"#;
    let loop_written = r#"defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = chain
variable set variable_name = n integer_value = 3
variable set variable_name = pre string_value = ".chain.link_"
marker create marker_name = .chain.ground.top location = 0, 0, 0
for variable_name = i start_value = 1 end_value = (n)
  part create rigid_body name_and_position part_name = (eval(pre // RTOI(i))) location = 0, (-(i - 1) * 100), 0
  part modify rigid_body mass_properties part_name = (eval(pre // RTOI(i))) mass = 0.5 ixx = 417 iyy = 417 izz = 417
  marker create marker_name = (eval(pre // RTOI(i) // ".top")) location = 0, (-(i - 1) * 100), 0
  marker create marker_name = (eval(pre // RTOI(i) // ".bottom")) location = 0, (-i * 100), 0
  if condition = (i == 1)
    constraint create joint revolute joint_name = .chain.pin_1 i_marker_name = .chain.link_1.top j_marker_name = .chain.ground.top
  else
    constraint create joint revolute joint_name = (eval(".chain.pin_" // RTOI(i))) i_marker_name = (eval(pre // RTOI(i) // ".top")) j_marker_name = (eval(pre // RTOI(i - 1) // ".bottom"))
  end
end
"#;
    let dataset = |text: &str| {
        simulate::view_dataset_text(text)
            .unwrap_or_else(|_| panic!("read"))
            .0
    };
    let looped = dataset(loop_typed);
    assert_eq!(looped, dataset(loop_written));
    assert_eq!(looped.matches("JOINT/").count(), 3, "{looped}");
    // A beginning more than one name's, of a parameter and of a command
    // word, is refused with the names it begins.
    let ambiguous = [
        "part cre rig name part_name = .m.Q loc = 0, 0, 0 pla = yes",
        "fo cre direct single_component_force single_component_force_name = .m.F",
    ];
    let report: String = ambiguous
        .iter()
        .map(|case| format!("{case}\n  => {}\n", check(case)))
        .collect();
    insta::assert_snapshot!(report);
}

/// What a View export of a bicycle (a public model) writes beside its
/// parts: `exact_coordinates`, the PART's EXACT (`all`, `none`, or
/// coordinates in any order and case); velocities stated again as View
/// expressions in the export's "expression definitions" (`vx =
/// (.m.speed)`), which keep the values the create command wrote; and a
/// View function (`function create`), which only View's own expressions
/// call: passed over.
#[test]
fn exact_coordinates_restated_velocities_and_view_functions_are_read() {
    let text = r#"defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = m
variable create variable_name = .m.speed units = "velocity" real_value = 100.0
part create rigid_body name_and_position part_name = .m.P location = 10, 0, 0 exact_coordinates = z, X
part create rigid_body initial_velocity part_name = .m.P vy = 100.0
marker create marker_name = .m.P.A location = 0, 0, 0
part create rigid_body mass_properties part_name = .m.P mass = 1 center_of_mass_marker = .m.P.A ixx = 1 iyy = 1 izz = 1
part create point_mass name_and_position point_mass_name = .m.Q location = 0, 50, 0 exact_coordinates = all
marker create marker_name = .m.Q.B location = 0, 50, 0
part create point_mass mass_properties point_mass_name = .m.Q mass = 2 center_of_mass_marker = .m.Q.B
part create rigid_body name_and_position part_name = .m.R location = 0, 0, 30 exact_coordinates = none
marker create marker_name = .m.R.C location = 0, 0, 30
part create rigid_body mass_properties part_name = .m.R mass = 1 center_of_mass_marker = .m.R.C ixx = 1 iyy = 1 izz = 1
function create function_name = .double text_of_expression = "2 * x" type = real
part modify rigid_body initial_velocity part_name = .m.P vy = (.m.speed)
"#;
    let (dataset, _) = simulate::view_dataset_text(text).unwrap_or_else(|unread| match unread {
        Unread::Refused(errors) => panic!("{}", render(text, None, &errors)),
        Unread::Unchecked(problems) => panic!("{problems:?}"),
    });
    let statement = |head: &str| -> String {
        let start = dataset
            .find(head)
            .unwrap_or_else(|| panic!("{head} in {dataset}"));
        let rest = &dataset[start + head.len()..];
        let end = rest
            .find(|c: char| c.is_ascii_uppercase() && rest.starts_with(c))
            .unwrap_or(0);
        let end = rest[end..]
            .find("\nPART/")
            .or_else(|| rest[end..].find("\nPOINT_MASS/"))
            .or_else(|| rest[end..].find("\nMARKER/"))
            .map_or(rest.len(), |at| at + end);
        rest[..end].to_string()
    };
    let p = statement("PART/2\n");
    assert!(p.contains(", EXACT = X:Z\n"), "{p}");
    assert!(p.contains(", VY = 100.0"), "{p}");
    let q = statement("POINT_MASS/");
    assert!(q.contains(", EXACT = X:Y:Z\n"), "{q}");
    assert!(!statement("PART/3\n").contains("EXACT"), "{dataset}");
    // A word that is no coordinate is wrong at its place; a point mass
    // has no angles.
    let report: String = [
        "part create rigid_body name_and_position part_name = .m.P exact_coordinates = x, w",
        "part create point_mass name_and_position point_mass_name = .m.Q exact_coordinates = psi",
    ]
    .iter()
    .map(|case| format!("{case}\n  => {}\n", check(case)))
    .collect();
    insta::assert_snapshot!(report);
}

/// View's general motion (`ude create instance` of
/// `.MDI.Constraints.general_motion`, as View exports it: an instance
/// whose variables give its markers and, per component, a type, a
/// function and initial conditions) drives a crank on its revolute joint
/// as a motion on the joint does: a displacement, a velocity and an
/// acceleration of its rotation (types 1, 2, 3), the other components
/// free (0). A VARIABLE reads the torque of its rotation's motion by its
/// name in the instance (`.m.general_motion_1.motion_r3`), as the joint
/// motion's.
#[test]
fn a_general_motion_drives_as_a_motion_on_the_joint() {
    let model = |driver: &str| {
        let motion = if driver.contains("general_motion") {
            ".m.general_motion_1.motion_r3"
        } else {
            ".m.drive"
        };
        format!(
            r#"defaults units length = mm angle = deg force = newton mass = kg time = sec
model create model_name = m
marker create marker_name = .m.ground.O location = 0, 0, 0
part create rigid_body name_and_position part_name = .m.crank location = 0, 0, 0
marker create marker_name = .m.crank.A location = 0, 0, 0
marker create marker_name = .m.crank.CM location = 100, 0, 0
part create rigid_body mass_properties part_name = .m.crank mass = 1 center_of_mass_marker = .m.crank.CM ixx = 10 iyy = 10 izz = 10
constraint create joint revolute joint_name = .m.pin i_marker_name = .m.crank.A j_marker_name = .m.ground.O
force create body gravitational gravity_field_name = .m.g y_component_gravity = -9806.65
{driver}
data_element create variable variable_name = .m.torque function = "MOTION({motion}, 0, 8, .m.ground.O)"
"#
        )
    };
    let general = |kind: u8, function: &str, ic_velo: f64| {
        let mut text = "ude create instance instance_name = .m.general_motion_1 definition_name = .MDI.Constraints.general_motion location = 0, 0, 0 orientation = 0, 0, 0\nvariable modify variable_name = .m.general_motion_1.i_marker object_value = (.m.crank.A)\nvariable modify variable_name = .m.general_motion_1.j_marker object_value = (.m.ground.O)\nvariable modify variable_name = .m.general_motion_1.constraint object_value = (.m.pin)\n".to_string();
        for component in ["t1", "t2", "t3", "r1", "r2", "r3"] {
            let (own_kind, own_function) = if component == "r3" {
                (kind, function)
            } else {
                (0, "0 * time")
            };
            text.push_str(&format!(
                "variable modify variable_name = .m.general_motion_1.{component}_type integer_value = {own_kind}\nvariable modify variable_name = .m.general_motion_1.{component}_func string_value = \"{own_function}\"\nvariable modify variable_name = .m.general_motion_1.{component}_ic_disp real_value = 0.0\nvariable modify variable_name = .m.general_motion_1.{component}_ic_velo real_value = {}\n",
                if component == "r3" { ic_velo } else { 0.0 }
            ));
        }
        text.push_str("ude modify instance instance_name = .m.general_motion_1");
        text
    };
    let on_joint = |derivative: &str, function: &str, velocity_ic: &str| {
        format!(
            "constraint create motion_generator motion_name = .m.drive type_of_freedom = rotational joint_name = .m.pin time_derivative = {derivative} function = \"{function}\"{velocity_ic}"
        )
    };
    let cases = [
        (
            general(1, "30d * time + 10d * sin(time)", 0.0),
            on_joint("displacement", "30d * time + 10d * sin(time)", ""),
        ),
        (
            general(2, "30d + 10d * cos(time)", 0.0),
            on_joint("velocity", "30d + 10d * cos(time)", ""),
        ),
        // An acceleration from rest.
        (
            general(3, "50d * sin(time)", 0.0),
            on_joint("acceleration", "50d * sin(time)", ""),
        ),
    ];
    for (driven, reference) in &cases {
        let (columns, a) = view_rows(&model(driven), 1.0, 10);
        let (reference_columns, b) = view_rows(&model(reference), 1.0, 10);
        let crank: Vec<usize> = columns
            .iter()
            .enumerate()
            .filter(|(_, name)| name.starts_with("PART/") || name.starts_with("VARIABLE/"))
            .map(|(at, _)| at)
            .collect();
        assert_eq!(crank.len(), 14, "{columns:?}");
        for (row_a, row_b) in a.iter().zip(&b) {
            for &at in &crank {
                let other = reference_columns
                    .iter()
                    .position(|name| *name == columns[at])
                    .expect("the same part");
                assert!(
                    (row_a[at] - row_b[other]).abs() <= 1e-7 * row_b[other].abs().max(1.0),
                    "{}: {} against {} at t = {}",
                    columns[at],
                    row_a[at],
                    row_b[other],
                    row_a[0]
                );
            }
        }
        // The crank has turned.
        let q0 = columns
            .iter()
            .position(|name| name.ends_with(".q0"))
            .expect("q0");
        assert!(a.last().expect("rows")[q0] < 0.999, "{driven}");
    }
    // A type it does not know, and a function naming nothing the file
    // creates, are refused at the variable that gives them.
    let report: String = [
        general(4, "time", 0.0),
        general(1, "DX(.m.crank.NONE)", 0.0),
    ]
    .iter()
    .map(|driver| {
        let text = model(driver);
        match view_model(&text) {
            Ok(_) => "read\n".to_string(),
            Err(errors) => format!("{}\n", errors.trim_end()),
        }
    })
    .collect();
    insta::assert_snapshot!(report);
}
