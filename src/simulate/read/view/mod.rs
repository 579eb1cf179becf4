//! An Adams View command file (`.cmd`) read as the solver dataset Adams
//! View writes for it (File > Export > Adams Solver Dataset), so that the
//! dataset reader simulates it: parts, point masses, markers, joints, motions, forces and
//! data elements become the statements they stand for, each at the place of
//! its command in the `.cmd`.
//!
//! What View does on the way is done here too:
//! - **Places.** A `location` and `orientation` (body 3-1-3 angles) are
//!   relative to `relative_to`, else to the `defaults coordinate_system`
//!   in force (a part, a marker or the model); a marker is then placed on
//!   its part by its origin and axes (`QP`, `ZP`, `XP`).
//! - **Units.** `defaults units` become `UNITS`. Angles are in the angle
//!   unit (degrees unless `angle = rad`; a `d` suffix is always degrees)
//!   and so are the angular parts of stiffness, damping and velocities.
//! - **Names.** A name is full (`.model.PART_2.MARKER_1`) or any tail of
//!   one (`PART_2.MARKER_1`); each object takes its `adams_id`, or the next
//!   free id of its kind. Function expressions name markers and objects:
//!   each name becomes its id.
//! - **Mass from geometry.** A part whose mass properties are a
//!   `material_type` or a `density` takes its mass, centre of mass and
//!   inertia from its solids (block, cylinder, frustum, ellipsoid, torus,
//!   link) at that density.
//! - **Later commands.** `modify` commands change what a `create` made
//!   (View writes every function after the objects it reads), and
//!   `attributes ... active = off` leaves an element out.
//! - **Elements.** Joints and primitives, general constraints, motions, single-component
//!   forces, force and torque vectors, general forces, spring-dampers,
//!   bushings, beams, contacts (their solids written as GRAPHICS), gravity,
//!   variables, differential equations, function requests and sensors.
//! - **The run.** The last `simulation single_run transient` (alone or in
//!   a `simulation script`) gives the end time and output steps.
//!
//! A command that would change the motion and is not read is refused at its
//! place; commands that only draw or arrange (colours, icons, views,
//! groups, points) are passed over.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;

use compact_str::CompactString;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};

use super::commands::RunCommands;
use crate::check::Checked;
use crate::model::{
    Argument, Dataset, FileKind, ModelCheck, Statement, Value, ValueItem, view_key as key,
    view_vocabulary,
};
use crate::simulate::error::SimulateError;
use crate::span::Span;

/// A View command file as a solver dataset, with its run.
pub struct ViewDataset {
    /// The statements, each at the place of the command it comes from.
    pub dataset: Dataset,
    /// The end time and output steps of its last transient simulation.
    pub run: Option<RunCommands>,
    /// What the reading passed over that a user may want to know.
    pub notes: Vec<(String, Span)>,
}

mod elements;
mod library;
mod solids;
mod write;

use elements::{
    Becomes, ELEMENTS, JOINT_PARAMETERS, MEASURE, NOTED, PASSED_OVER, TWO_MARKERS, WIRES, becomes,
    constraint_kind,
};

/// A frame: its origin and axes (columns) in the ground's.
#[derive(Clone, Copy, Debug)]
struct Frame {
    origin: Vector3<f64>,
    axes: Matrix3<f64>,
}

impl Frame {
    const GROUND: Frame = Frame {
        origin: Vector3::new(0.0, 0.0, 0.0),
        axes: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
    };

    /// The frame `local` gives in this one.
    fn then(&self, local: &Frame) -> Frame {
        Frame {
            origin: self.origin + self.axes * local.origin,
            axes: self.axes * local.axes,
        }
    }

    /// `global` seen from this frame.
    fn seen(&self, global: &Frame) -> Frame {
        Frame {
            origin: self.axes.transpose() * (global.origin - self.origin),
            axes: self.axes.transpose() * global.axes,
        }
    }
}

/// What a name stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Entity {
    Part(usize),
    Marker(usize),
    Element(usize),
    Material(usize),
    Geometry(usize),
    /// A design variable's value (`variable create ... real_value = v`).
    Design(usize),
    /// A point (`point create`), where a measure reads it.
    Point(usize),
    /// A statement the reader writes itself, by its id: a general
    /// motion's MOTION (`.m.general_motion_1.motion_t3`).
    Written(u64),
    Model,
}

/// A point on a part (`point create`): a measure of it is a measure of a
/// marker made there when a function or a VARIABLE needs it.
struct Point {
    part: usize,
    frame: Frame,
    span: Span,
    /// The id of the marker made at it, once made.
    marker: Option<u64>,
}

/// A geometry (`geometry create shape ...`): its command and shape, its
/// id, and whether a contact meets it (then a GRAPHICS is written for it).
struct Geometry {
    command: usize,
    shape: String,
    id: Option<u64>,
    /// The part it is on, by its name's path.
    part: Option<usize>,
    met: bool,
}

/// A rigid part.
struct Part {
    name: String,
    id: Option<u64>,
    span: Span,
    frame: Frame,
    ground: bool,
    /// A point mass (`part create point_mass`): a POINT_MASS, a mass
    /// without inertia or rotation.
    point_mass: bool,
    /// The `mass_properties` command.
    mass: Option<usize>,
    /// The `initial_velocity` command.
    velocity: Option<usize>,
    /// The solids (`geometry create shape` commands) on it.
    solids: Vec<usize>,
    /// The id of its centre-of-mass marker, once its PART is written.
    centre_marker: Option<u64>,
    /// The id of a marker at its frame, once a measure of its orientation
    /// needs one.
    frame_marker: Option<u64>,
    /// The features (`geometry create feature`: blends, chamfers, holes)
    /// on its solids, by command.
    features: Vec<usize>,
    /// Not made inactive (`part attributes ... active = off`).
    active: bool,
    /// The coordinates the initial-conditions analysis holds
    /// (`exact_coordinates`), as the solver's EXACT names them, and where
    /// they are given.
    exact: Option<(Vec<&'static str>, Span)>,
}

/// A marker (or floating marker) on a part.
struct Marker {
    id: Option<u64>,
    span: Span,
    part: usize,
    frame: Frame,
    floating: bool,
}

/// An element: its kind, the commands that made and changed it.
struct Element {
    /// The solver statement, and the keywords its words give.
    statement: &'static str,
    flags: Vec<&'static str>,
    parameters: &'static [&'static [(&'static str, Becomes)]],
    id: Option<u64>,
    span: Span,
    /// `(command, argument)` of each parameter given, the last for each.
    given: Vec<(CompactString, usize, usize)>,
    active: bool,
    /// Its name as the create command wrote it.
    name: String,
}

/// The reader's state.
struct Reader<'d> {
    view: &'d Dataset,
    trees: HashMap<(usize, CompactString), &'d Checked>,
    names: HashMap<String, Entity>,
    /// Every tail of every full name, with what it stands for.
    tails: HashMap<String, Vec<Entity>>,
    model: Option<String>,
    parts: Vec<Part>,
    markers: Vec<Marker>,
    elements: Vec<Element>,
    points: Vec<Point>,
    geometries: Vec<Geometry>,
    densities: Vec<f64>,
    designs: Vec<f64>,
    /// The function measures being read into a function (against loops).
    reading: Vec<usize>,
    /// The user-defined element instances other than a controls plant's
    /// (`ude create instance` of a force, of a constraint such as View's
    /// general motion, of an Adams Machinery part): the library springs
    /// are read, any other is refused unless made inactive.
    user_elements: Vec<(String, usize, bool)>,
    /// The command that sets each variable last (`variable create` or
    /// `modify`), by full name: a library spring's values.
    instance_variables: HashMap<String, usize>,
    /// Every user-defined element's instance: its full name and its
    /// definition's (what names inside it are part of).
    instances: Vec<(String, String)>,
    /// The frame locations are given in by default.
    coordinates: Frame,
    degrees: bool,
    /// How orientations are given (`defaults units orientation_type`).
    orientation_type: Orientations,
    /// Locations are given as cylindrical coordinates, `r, θ, z` (θ in the
    /// angle unit; `defaults units coordinate_system_type = cylindrical`).
    cylindrical: bool,
    units: [(&'static str, &'static str); 4],
    units_span: Span,
    run: Option<RunCommands>,
    errors: Vec<SimulateError>,
    notes: Vec<(String, Span)>,
}

/// The words of `statement` without its verb (`CREATE`, `MODIFY`), and the verb.
fn words_and_verb(statement: &Statement) -> (String, Option<&str>) {
    let words: Vec<&str> = statement.name.split(' ').collect();
    match words
        .iter()
        .position(|word| matches!(*word, "CREATE" | "MODIFY"))
    {
        Some(at) => {
            let mut rest = words[..at].to_vec();
            rest.extend(&words[at + 1..]);
            (rest.join(" "), Some(words[at]))
        }
        None => (words.join(" "), None),
    }
}

/// The parameter that names the part of a `part ... mass_properties` or
/// `initial_velocity` command with words `words`: a point mass's or a
/// rigid body's.
fn part_keyword(words: &str) -> &'static str {
    if words.starts_with("PART POINT_MASS") {
        "POINT_MASS_NAME"
    } else {
        "PART_NAME"
    }
}

/// The label of a View command for messages: its words, lower case.
fn label(statement: &Statement) -> String {
    statement.name.to_ascii_lowercase().to_string()
}

/// A View unit name, or the solver's, as the solver's.
fn solver_unit(kind: &str, name: &str) -> Option<&'static str> {
    let name = name.trim_matches('"').to_ascii_uppercase();
    let table: &[(&[&str], &str)] = match kind {
        "LENGTH" => &[
            (&["MM", "MILLIMETER", "MILLIMETERS"], "MILLIMETER"),
            (&["CM", "CENTIMETER", "CENTIMETERS"], "CENTIMETER"),
            (&["METER", "METERS", "M"], "METER"),
            (&["KM", "KILOMETER", "KILOMETERS"], "KILOMETER"),
            (&["INCH", "INCHES", "IN"], "INCH"),
            (&["FOOT", "FEET", "FT"], "FOOT"),
            (&["MILE", "MILES"], "MILE"),
            (&["MICRON", "MICROMETER"], "MICROMETER"),
        ],
        "MASS" => &[
            (&["KG", "KILOGRAM", "KILOGRAMS"], "KILOGRAM"),
            (&["GRAM", "GRAMS", "G"], "GRAM"),
            (&["POUND_MASS", "LBM"], "POUND_MASS"),
            (&["KPOUND_MASS"], "KPOUND_MASS"),
            (&["SLUG", "SLUGS"], "SLUG"),
            (&["OUNCE_MASS"], "OUNCE_MASS"),
            (&["TONNE", "MEGAGRAM"], "TONNE"),
        ],
        "FORCE" => &[
            (&["NEWTON", "NEWTONS", "N"], "NEWTON"),
            (&["KNEWTON", "KILONEWTON"], "KNEWTON"),
            (&["MILLINEWTON"], "MILLINEWTON"),
            (&["MEGANEWTON"], "MEGANEWTON"),
            (&["DYNE", "DYNES"], "DYNE"),
            (&["POUND_FORCE", "LBF"], "POUND_FORCE"),
            (&["KPOUND_FORCE"], "KPOUND_FORCE"),
            (&["KG_FORCE", "KILOGRAM_FORCE"], "KILOGRAM_FORCE"),
            (&["OUNCE_FORCE"], "OUNCE_FORCE"),
        ],
        _ => &[
            (&["SEC", "SECOND", "SECONDS", "S"], "SECOND"),
            (
                &["MILLISEC", "MILLISECOND", "MILLISECONDS", "MS"],
                "MILLISECOND",
            ),
            (&["MINUTE", "MINUTES", "MIN"], "MINUTE"),
            (&["HOUR", "HOURS", "HR"], "HOUR"),
        ],
    };
    table
        .iter()
        .find(|(names, _)| names.contains(&name.as_str()))
        .map(|&(_, solver)| solver)
}

/// Reads the View command file `view` (checked: `check`) as a solver
/// dataset. Every command that would change the motion and is not read is
/// refused at its place.
pub fn solver_dataset(
    view: &Dataset,
    check: &ModelCheck,
) -> Result<ViewDataset, Vec<SimulateError>> {
    let mut trees = HashMap::new();
    for found in &check.expressions {
        if let Some(tree) = &found.checked {
            trees.insert((found.statement, found.keyword.clone()), tree);
        }
    }
    let mut reader = Reader {
        view,
        trees,
        names: HashMap::new(),
        tails: HashMap::new(),
        model: None,
        parts: Vec::new(),
        markers: Vec::new(),
        elements: Vec::new(),
        points: Vec::new(),
        geometries: Vec::new(),
        densities: Vec::new(),
        designs: Vec::new(),
        reading: Vec::new(),
        user_elements: Vec::new(),
        instance_variables: HashMap::new(),
        instances: Vec::new(),
        coordinates: Frame::GROUND,
        degrees: true,
        orientation_type: Orientations::BODY_313,
        cylindrical: false,
        units: [
            ("FORCE", "NEWTON"),
            ("MASS", "KILOGRAM"),
            ("LENGTH", "MILLIMETER"),
            ("TIME", "SECOND"),
        ],
        units_span: Span::at(0),
        run: None,
        errors: Vec::new(),
        notes: Vec::new(),
    };
    reader.ground(None, Span::at(0));
    for index in 0..view.statements.len() {
        reader.command(index);
    }
    let statements = reader.write();
    reader.check_finite(&statements);
    if !reader.errors.is_empty() {
        return Err(SimulateError::grouped(reader.errors));
    }
    Ok(ViewDataset {
        dataset: Dataset {
            kind: FileKind::Adm,
            title: None,
            statements,
            problems: Vec::new(),
        },
        run: reader.run,
        notes: reader.notes,
    })
}

impl<'d> Reader<'d> {
    /// Every number the reading wrote is finite: a place, an axis or a mass
    /// computed from numbers near the doubles' limit (about 1e308) can
    /// overflow, and is wrong at the command it comes from (one error a
    /// statement).
    fn check_finite(&mut self, statements: &[Statement]) {
        for statement in statements {
            let overflowed =
                statement
                    .arguments
                    .iter()
                    .find_map(|argument| match &argument.value {
                        Value::List(items) => items
                            .iter()
                            .find(|item| {
                                item.text
                                    .parse::<f64>()
                                    .is_ok_and(|value| !value.is_finite())
                            })
                            .map(|item| (argument, item.text.clone())),
                        _ => None,
                    });
            if let Some((argument, value)) = overflowed {
                self.wrong(
                    format!(
                        "{}/{} {} computes to {value}: the numbers it is made from reach the doubles' limit (about 1e308): give smaller values",
                        statement.name,
                        statement.id.unwrap_or(0),
                        argument.keyword
                    ),
                    argument.span,
                );
            }
        }
    }

    fn refuse(&mut self, statement: &Statement, reason: String, span: Span) {
        self.errors.push(SimulateError::Unsupported {
            statement: format!("`{}`", label(statement)),
            reason,
            span,
        });
    }

    fn wrong(&mut self, message: String, span: Span) {
        self.errors.push(SimulateError::Model { message, span });
    }

    /// Enters `name` (full, upper case) for `entity`, with its tails.
    fn name(&mut self, name: String, entity: Entity) {
        let mut rest = name.as_str();
        while let Some((_, tail)) = rest.split_once('.') {
            self.tails.entry(tail.to_string()).or_default().push(entity);
            rest = tail;
        }
        self.names.insert(name, entity);
    }

    /// What `name` (full or a tail) stands for.
    fn find(&self, name: &str) -> Option<Entity> {
        let name = key(name);
        if let Some(entity) = self.names.get(&name) {
            return Some(*entity);
        }
        match self.tails.get(&name).map(Vec::as_slice) {
            Some([entity]) => Some(*entity),
            _ => None,
        }
    }

    /// The full name of a new object named `name` in the model.
    fn full(&self, name: &str) -> String {
        let name = key(name);
        match &self.model {
            Some(model) if !name.contains('.') => format!("{model}.{name}"),
            _ => name,
        }
    }

    /// The ground part, created with the model.
    fn ground(&mut self, model: Option<&str>, span: Span) {
        let name = match model {
            Some(model) => format!("{model}.GROUND"),
            None => "GROUND".to_string(),
        };
        if self.find(&name).is_some() {
            return;
        }
        self.parts.push(Part {
            name: name.clone(),
            id: None,
            span,
            frame: Frame::GROUND,
            ground: true,
            point_mass: false,
            mass: None,
            velocity: None,
            solids: Vec::new(),
            centre_marker: None,
            frame_marker: None,
            features: Vec::new(),
            active: true,
            exact: None,
        });
        self.name(name, Entity::Part(self.parts.len() - 1));
    }

    /// Gives `part` the full name `new`; the names under its old one (its
    /// markers') are entered under the new one too.
    fn rename_part(&mut self, part: usize, new: String) {
        let old = self.parts[part].name.clone();
        self.names.remove(&old);
        for tails in self.tails.values_mut() {
            tails.retain(|entity| *entity != Entity::Part(part));
        }
        let renamed: Vec<(String, Entity)> = self
            .names
            .iter()
            .filter(|(name, _)| name.starts_with(&format!("{old}.")))
            .map(|(name, entity)| (format!("{new}{}", &name[old.len()..]), *entity))
            .collect();
        for (name, entity) in renamed {
            self.name(name, entity);
        }
        self.parts[part].name = new.clone();
        self.name(new, Entity::Part(part));
    }

    /// The argument `keyword` of command `index`, with its index.
    fn argument(&self, index: usize, keyword: &str) -> Option<(usize, &'d Argument)> {
        self.view.statements[index]
            .arguments
            .iter()
            .enumerate()
            .find(|(_, argument)| argument.keyword == keyword)
    }

    /// The items of a list argument.
    fn items(&self, index: usize, keyword: &str) -> Option<&'d [ValueItem]> {
        match &self.argument(index, keyword)?.1.value {
            Value::List(items) => Some(items),
            _ => None,
        }
    }

    /// The object command `index` is about: the value of its first
    /// `*_name` parameter, as written.
    fn object_name(&self, index: usize) -> Option<String> {
        self.view.statements[index]
            .arguments
            .iter()
            .find(|argument| argument.keyword.ends_with("_NAME"))
            .and_then(|argument| match &argument.value {
                Value::List(items) => items.first().map(|item| item.text.to_string()),
                _ => None,
            })
    }

    /// The items of a list argument as written (names).
    fn names(&self, index: usize, keyword: &str) -> Vec<String> {
        self.items(index, keyword)
            .unwrap_or_default()
            .iter()
            .map(|item| item.text.to_string())
            .collect()
    }

    /// Refuses `argument` of `statement`: a parameter the reading does not
    /// know.
    fn refuse_unread(&mut self, statement: &Statement, argument: &Argument) {
        let reason = view_vocabulary::ambiguity(&statement.name, Some(&argument.keyword))
            .unwrap_or_else(|| {
                format!(
                    "sets {}, which mbexpr does not read",
                    argument.keyword.to_ascii_lowercase()
                )
            });
        self.refuse(statement, reason, argument.span);
    }

    /// The single word of a list argument, upper case.
    fn word(&self, index: usize, keyword: &str) -> Option<String> {
        self.items(index, keyword)
            .and_then(|items| items.first())
            .map(|item| key(&item.text))
    }

    /// A switch: `on`, `yes` or `true`, or `off`, `no` or `false`; another
    /// word is wrong at `span`.
    fn switch(&mut self, index: usize, keyword: &str, span: Span) -> Option<bool> {
        match self.word(index, keyword).unwrap_or_default().as_str() {
            "ON" | "YES" | "TRUE" => Some(true),
            "OFF" | "NO" | "FALSE" => Some(false),
            _ => {
                self.wrong(
                    format!("{} is on or off", keyword.to_ascii_lowercase()),
                    span,
                );
                None
            }
        }
    }

    /// The numbers of a list argument; angles (`angle`) in radians.
    fn numbers(&mut self, index: usize, keyword: &str, angle: bool) -> Option<Vec<f64>> {
        let (_, argument) = self.argument(index, keyword)?;
        let Value::List(items) = &argument.value else {
            return None;
        };
        let mut values = Vec::new();
        for item in items {
            let degrees = item.text.trim().ends_with(['d', 'D']);
            match item.number() {
                Some(value) if angle && !degrees && self.degrees => values.push(value * PI / 180.0),
                Some(value) => values.push(value),
                None => {
                    self.wrong(
                        format!(
                            "{}: `{}` is not a number mbexpr reads (a value with its unit, or a View expression of what mbexpr does not evaluate: a function of the model, a name no variable before has, a result out of range): give the number",
                            keyword.to_ascii_lowercase(),
                            item.text
                        ),
                        item.span,
                    );
                    return None;
                }
            }
        }
        Some(values)
    }

    /// `location` and `orientation` of command `index`, relative to
    /// `relative_to` or the default coordinate system.
    fn placed(&mut self, index: usize) -> Frame {
        let statement = &self.view.statements[index];
        let reference = match self.argument(index, "RELATIVE_TO") {
            Some((_, argument)) => match self.frame_of(index, "RELATIVE_TO") {
                Some(frame) => frame,
                None => {
                    self.wrong(
                        "relative_to names no model, part or marker the file creates before".into(),
                        argument.span,
                    );
                    Frame::GROUND
                }
            },
            None => self.coordinates,
        };
        let location = self.numbers(index, "LOCATION", false).unwrap_or_default();
        let orientation = self.numbers(index, "ORIENTATION", true).unwrap_or_default();
        for (keyword, values) in [("LOCATION", &location), ("ORIENTATION", &orientation)] {
            if !values.is_empty() && values.len() != 3 {
                let span = statement.place_of(keyword, keyword.len());
                self.wrong(
                    format!("{} takes three numbers", keyword.to_ascii_lowercase()),
                    span,
                );
            }
        }
        let three = |values: &[f64]| match values {
            [a, b, c] => [*a, *b, *c],
            _ => [0.0; 3],
        };
        let [mut x, mut y, z] = three(&location);
        if self.cylindrical && location.len() == 3 {
            // r, θ, z: θ is an angle (in the angle unit, or with `d`).
            let angle = self
                .numbers(index, "LOCATION", true)
                .map_or(0.0, |values| values[1]);
            (x, y) = (location[0] * angle.cos(), location[0] * angle.sin());
        }
        reference.then(&Frame {
            origin: Vector3::new(x, y, z),
            axes: self.orientation_type.axes(three(&orientation)),
        })
    }

    /// Whether a modify command `index` places its object anew: it gives
    /// a location or orientation, and none of its placing arguments is a
    /// View expression (those restate the place the create command wrote:
    /// `(LOC_RELATIVE_TO({0, 0, 0}, .model.ground.A))`).
    fn moves(&self, index: usize) -> bool {
        let placing = ["LOCATION", "ORIENTATION", "RELATIVE_TO"]
            .map(|keyword| self.argument(index, keyword).map(|(_, argument)| argument));
        placing[..2].iter().any(Option::is_some)
            && !placing
                .iter()
                .flatten()
                .any(|argument| view_expression(argument))
    }

    /// A design variable: its single real value, which functions read.
    fn design_variable(&mut self, index: usize) {
        let Some(name) = self.word(index, "VARIABLE_NAME") else {
            return;
        };
        self.instance_variables.insert(self.full(&name), index);
        // A real value, or an integer one (`variable set ... integer_value`).
        let Some((keyword, argument)) = ["REAL_VALUE", "INTEGER_VALUE"]
            .into_iter()
            .find_map(|keyword| Some((keyword, self.argument(index, keyword)?.1)))
        else {
            return;
        };
        if view_expression(argument) {
            return;
        }
        let Some([value]) =
            self.numbers(index, keyword, false)
                .as_deref()
                .map(|values| match values {
                    [value] => [*value],
                    _ => [f64::NAN],
                })
        else {
            return;
        };
        match self.find(&name) {
            Some(Entity::Design(design)) => self.designs[design] = value,
            _ => {
                self.designs.push(value);
                let full = self.full(&name);
                self.name(full, Entity::Design(self.designs.len() - 1));
            }
        }
    }

    /// A user-defined element's instance: View's library springs are
    /// read; a controls plant's (Adams Controls: the model's inputs and
    /// outputs, named) is passed over; any other (a general motion, an
    /// Adams Machinery cam or follower, whose definitions make parts,
    /// constraints and forces) is refused unless made inactive later.
    fn user_defined(&mut self, index: usize) {
        let definition = self.word(index, "DEFINITION_NAME").unwrap_or_default();
        let Some(name) = self.word(index, "INSTANCE_NAME") else {
            return;
        };
        if self.view.statements[index].name.contains(" CREATE ") {
            if !definition.starts_with("CONTROLS.") {
                self.user_elements.push((self.full(&name), index, true));
            }
            self.instances.push((self.full(&name), definition));
        }
    }

    /// Why `name`, which names nothing the file creates, is not known: it
    /// is inside a user-defined element's instance (a controls block's
    /// variable), whose insides mbexpr does not read.
    fn inside_instance(&self, name: &str) -> Option<String> {
        let full = self.full(name);
        self.instances
            .iter()
            .find(|(instance, _)| {
                full.strip_prefix(instance.as_str())
                    .is_some_and(|rest| rest.starts_with('.'))
            })
            .map(|(instance, definition)| {
                format!(
                    "{name} is inside {instance}, an instance of the View library element {definition}, whose insides mbexpr does not read: mbexpr simulates the model's own elements"
                )
            })
    }

    /// The frame of the model, part or marker argument `keyword` names.
    fn frame_of(&self, index: usize, keyword: &str) -> Option<Frame> {
        let name = self.word(index, keyword)?;
        match self.find(&name)? {
            Entity::Model => Some(Frame::GROUND),
            Entity::Part(part) => Some(self.parts[part].frame),
            Entity::Marker(marker) => Some(self.markers[marker].frame),
            _ => None,
        }
    }

    /// The id of argument `keyword` when it is a whole number.
    fn id(&mut self, index: usize, keyword: &str) -> Option<u64> {
        let items = self.items(index, keyword)?;
        let item = items.first()?;
        match item.text.trim().parse::<u64>() {
            Ok(id) if id > 0 && id <= crate::model::LARGEST_ID => Some(id),
            _ => {
                self.wrong("adams_id must be a positive whole number".into(), item.span);
                None
            }
        }
    }

    fn command(&mut self, index: usize) {
        let statement = &self.view.statements[index];
        let (words, verb) = words_and_verb(statement);
        let words = words.as_str();
        match (words, verb) {
            ("MODEL", Some("CREATE")) => {
                if let Some(name) = self.word(index, "MODEL_NAME") {
                    let name = key(&name);
                    // A model named inside one the file made (Adams Controls'
                    // `.PM.Controls_Plant_1`, holding the plant's inputs and
                    // outputs) is a namespace of that model: its parts, the
                    // ground among them, stay the outer model's.
                    if let Some((outer, _)) = name.split_once('.')
                        && self.names.get(outer) == Some(&Entity::Model)
                    {
                        self.name(name, Entity::Model);
                        return;
                    }
                    self.model = Some(name.clone());
                    self.name(name.clone(), Entity::Model);
                    // The ground made before any model takes the model's name.
                    match self.names.get("GROUND") {
                        Some(&Entity::Part(ground)) => {
                            self.rename_part(ground, format!("{name}.GROUND"));
                            self.parts[ground].span = statement.span;
                        }
                        _ => self.ground(Some(&name), statement.span),
                    }
                }
            }
            ("DEFAULTS UNITS", None) => self.default_units(index),
            ("DEFAULTS COORDINATE_SYSTEM", None) => {
                match self.frame_of(index, "DEFAULT_COORDINATE_SYSTEM") {
                    Some(frame) => self.coordinates = frame,
                    None => {
                        let span = statement.place_of("DEFAULT_COORDINATE_SYSTEM", 7);
                        self.wrong(
                            "default_coordinate_system names no model, part or marker the file creates before".into(),
                            span,
                        );
                    }
                }
            }
            ("VARIABLE", Some(_)) | ("VARIABLE SET", None) => self.design_variable(index),
            ("UDE INSTANCE", Some(_)) => self.user_defined(index),
            ("MATERIAL", Some("MODIFY")) => {
                // A density given again as a View expression keeps the
                // value the create command wrote (see `view_expression`).
                if let Some(name) = self.word(index, "MATERIAL_NAME")
                    && let Some(Entity::Material(material)) = self.find(&name)
                    && self
                        .argument(index, "DENSITY")
                        .is_some_and(|(_, argument)| !view_expression(argument))
                    && let Some(density) = self
                        .numbers(index, "DENSITY", false)
                        .and_then(|values| values.first().copied())
                {
                    self.densities[material] = density;
                }
            }
            ("MATERIAL", Some("CREATE")) => {
                if let Some(name) = self.word(index, "MATERIAL_NAME") {
                    let density = self
                        .numbers(index, "DENSITY", false)
                        .and_then(|values| values.first().copied());
                    self.densities.push(density.unwrap_or(f64::NAN));
                    let entity = Entity::Material(self.densities.len() - 1);
                    let name = self.full(&name);
                    self.name(name, entity);
                }
            }
            ("PART RIGID_BODY NAME_AND_POSITION", Some(verb)) => self.part(index, verb, false),
            ("PART POINT_MASS NAME_AND_POSITION", Some(verb)) => self.part(index, verb, true),
            ("PART RIGID_BODY MASS_PROPERTIES" | "PART POINT_MASS MASS_PROPERTIES", Some(verb)) => {
                if let Some(part) = self.part_named(index, part_keyword(words)) {
                    // View's expression definitions state again, as View
                    // expressions, what the create command wrote evaluated.
                    let restated = verb == "MODIFY"
                        && self.parts[part].mass.is_some()
                        && statement.arguments.iter().any(view_expression);
                    if !restated {
                        self.parts[part].mass = Some(index);
                    }
                }
            }
            (
                "PART RIGID_BODY INITIAL_VELOCITY" | "PART POINT_MASS INITIAL_VELOCITY",
                Some(verb),
            ) => {
                if let Some(part) = self.part_named(index, part_keyword(words)) {
                    // View's expression definitions state the velocities
                    // again as View expressions (`vx = (.m.Init_Vel)`).
                    let restated = verb == "MODIFY"
                        && self.parts[part].velocity.is_some()
                        && statement.arguments.iter().any(view_expression);
                    if !restated {
                        self.parts[part].velocity = Some(index);
                    }
                }
            }
            ("MARKER", Some(verb)) => self.marker(index, verb == "MODIFY", false),
            ("POINT", Some(verb)) => self.point(index, verb == "MODIFY"),
            ("FLOATING_MARKER", Some("CREATE")) => self.marker(index, false, true),
            ("SIMULATION SINGLE_RUN TRANSIENT", None) => {
                self.transient(&run_parameters(statement), statement.span);
            }
            ("SIMULATION SCRIPT", Some(_)) => self.script(index),
            _ if words.starts_with("GEOMETRY SHAPE ") => self.solid(index, &words[15..]),
            _ if words.starts_with("GEOMETRY FEATURE ") => self.feature(index),
            _ if words.split(' ').nth(1) == Some("ATTRIBUTES") => self.attributes(index),
            _ => self.element(index, words, verb),
        }
    }

    fn default_units(&mut self, index: usize) {
        let statement = &self.view.statements[index];
        for argument in &statement.arguments {
            let Value::List(items) = &argument.value else {
                continue;
            };
            let Some(item) = items.first() else { continue };
            let value = key(&item.text);
            match argument.keyword.as_str() {
                "ANGLE" => match value.as_str() {
                    "DEG" | "DEGREE" | "DEGREES" => self.degrees = true,
                    "RAD" | "RADIAN" | "RADIANS" => self.degrees = false,
                    _ => self.wrong(
                        format!("angle = {}: mbexpr reads deg and rad", item.text),
                        item.span,
                    ),
                },
                kind @ ("LENGTH" | "MASS" | "FORCE" | "TIME") => match solver_unit(kind, &value) {
                    Some(unit) => {
                        for slot in &mut self.units {
                            if slot.0 == kind {
                                slot.1 = unit;
                            }
                        }
                        self.units_span = statement.span;
                    }
                    None => self.wrong(
                        format!(
                            "{} = {}: not a unit of {} mbexpr knows",
                            kind.to_ascii_lowercase(),
                            item.text,
                            kind.to_ascii_lowercase()
                        ),
                        item.span,
                    ),
                },
                "ORIENTATION_TYPE" => match Orientations::named(&value) {
                    Some(orientations) => self.orientation_type = orientations,
                    None => self.refuse(
                        statement,
                        format!(
                            "orients by {}: mbexpr reads angles of a body or space sequence of three axes (body313, View's default, body123, space321 ...)",
                            item.text
                        ),
                        argument.span,
                    ),
                },
                "COORDINATE_SYSTEM_TYPE" if value == "CYLINDRICAL" => self.cylindrical = true,
                "COORDINATE_SYSTEM_TYPE" if value == "CARTESIAN" => self.cylindrical = false,
                "COORDINATE_SYSTEM_TYPE" => self.refuse(
                    statement,
                    format!(
                        "places by {} coordinates: mbexpr reads cartesian ones (View's default) and cylindrical ones",
                        item.text
                    ),
                    argument.span,
                ),
                _ => {}
            }
        }
    }

    /// The part argument `keyword` of command `index` names.
    fn part_named(&mut self, index: usize, keyword: &str) -> Option<usize> {
        let name = self.word(index, keyword)?;
        match self.find(&name) {
            Some(Entity::Part(part)) => Some(part),
            _ => {
                let span = self.view.statements[index].place_of(keyword, keyword.len());
                self.wrong(
                    format!(
                        "{} names no part the file creates before",
                        keyword.to_ascii_lowercase()
                    ),
                    span,
                );
                None
            }
        }
    }

    /// A part (`part create rigid_body name_and_position`), or a point mass
    /// (`part create point_mass name_and_position`), created or moved.
    fn part(&mut self, index: usize, verb: &str, point_mass: bool) {
        let statement = &self.view.statements[index];
        let (name_keyword, new_name_keyword) = if point_mass {
            ("POINT_MASS_NAME", "NEW_POINT_MASS_NAME")
        } else {
            ("PART_NAME", "NEW_PART_NAME")
        };
        let Some(name) = self.word(index, name_keyword) else {
            return;
        };
        for argument in &statement.arguments {
            match argument.keyword.as_str() {
                keyword if keyword == name_keyword || keyword == new_name_keyword => {}
                "ADAMS_ID" | "LOCATION" | "ORIENTATION" | "RELATIVE_TO" | "COMMENTS"
                | "GROUND_PART" => {}
                "PLANAR" if self.word(index, "PLANAR").as_deref() == Some("NO") => {}
                "PLANAR_AXES" | "EXACT_COORDINATES" => {}
                _ => self.refuse_unread(statement, argument),
            }
        }
        let exact = self.exact_coordinates(index, point_mass);
        let id = self.id(index, "ADAMS_ID");
        let part = if verb == "CREATE" {
            let name = self.full(&name);
            self.parts.push(Part {
                name: name.clone(),
                id: None,
                span: statement.span,
                frame: Frame::GROUND,
                ground: false,
                point_mass,
                mass: None,
                velocity: None,
                solids: Vec::new(),
                centre_marker: None,
                frame_marker: None,
                features: Vec::new(),
                active: true,
                exact: None,
            });
            let part = self.parts.len() - 1;
            self.name(name, Entity::Part(part));
            part
        } else {
            match self.part_named(index, name_keyword) {
                Some(part) => part,
                None => return,
            }
        };
        if let Some(id) = id {
            self.parts[part].id = Some(id);
        }
        if let Some(exact) = exact {
            self.parts[part].exact = Some(exact);
        }
        if let Some(new_name) = self.word(index, new_name_keyword) {
            // The markers keep their part: their names are re-entered under
            // the new one.
            let old = self.parts[part].name.clone();
            let new = match old.rsplit_once('.') {
                Some((model, _)) if !new_name.contains('.') => format!("{model}.{new_name}"),
                _ => key(&new_name),
            };
            self.rename_part(part, new);
        }
        if verb == "CREATE" || self.moves(index) {
            if self.parts[part].ground {
                self.refuse(
                    statement,
                    "moves the ground part, which stays at the origin".into(),
                    statement.span,
                );
            } else {
                self.parts[part].frame = self.placed(index);
            }
        }
    }

    /// The coordinates a part's `exact_coordinates` holds in the
    /// initial-conditions analysis, as EXACT names them (`all`: every one
    /// the part has; `none`: none), and where they are given; `None` when
    /// the command does not set them. A word that is no coordinate is
    /// wrong at its place.
    fn exact_coordinates(
        &mut self,
        index: usize,
        point_mass: bool,
    ) -> Option<(Vec<&'static str>, Span)> {
        const COORDINATES: [&str; 6] = ["X", "Y", "Z", "PSI", "THETA", "PHI"];
        let (_, argument) = self.argument(index, "EXACT_COORDINATES")?;
        let span = argument.span;
        let own = if point_mass { 3 } else { 6 };
        let mut held = Vec::new();
        for item in self.items(index, "EXACT_COORDINATES").unwrap_or_default() {
            match key(&item.text).as_str() {
                "ALL" => held.extend_from_slice(&COORDINATES[..own]),
                "NONE" => {}
                word => match COORDINATES[..own].iter().find(|known| **known == word) {
                    Some(known) => held.push(*known),
                    None => {
                        self.wrong(
                            format!(
                                "exact_coordinates: `{}` is none of {}, all and none",
                                item.text,
                                COORDINATES[..own].join(", ").to_ascii_lowercase()
                            ),
                            item.span,
                        );
                        return None;
                    }
                },
            }
        }
        held.sort_by_key(|coordinate| COORDINATES.iter().position(|known| known == coordinate));
        held.dedup();
        Some((held, span))
    }

    /// A point on a part, kept for the measures that name it; otherwise
    /// it only draws, so nothing about it is refused (a point this cannot
    /// place is left out).
    fn point(&mut self, index: usize, modify: bool) {
        let Some(name) = self.word(index, "POINT_NAME") else {
            return;
        };
        let full = self.full(&name);
        let errors = self.errors.len();
        let frame = if modify {
            self.moves(index).then(|| self.placed(index))
        } else {
            Some(self.placed(index))
        };
        let placed = self.errors.len() == errors;
        self.errors.truncate(errors);
        match (modify, frame, self.find(&full)) {
            (true, Some(frame), Some(Entity::Point(point))) if placed => {
                self.points[point].frame = frame;
            }
            (false, Some(frame), _) if placed => {
                let owner = full.rsplit_once('.').map(|(owner, _)| owner.to_string());
                if let Some(Entity::Part(part)) = owner.and_then(|owner| self.find(&owner)) {
                    self.points.push(Point {
                        part,
                        frame,
                        span: self.view.statements[index].span,
                        marker: None,
                    });
                    self.name(full, Entity::Point(self.points.len() - 1));
                }
            }
            _ => {}
        }
    }

    fn marker(&mut self, index: usize, modify: bool, floating: bool) {
        let statement = &self.view.statements[index];
        let keyword = if floating {
            "FLOATING_MARKER_NAME"
        } else {
            "MARKER_NAME"
        };
        let Some(name) = self.word(index, keyword) else {
            return;
        };
        for argument in &statement.arguments {
            match argument.keyword.as_str() {
                "MARKER_NAME"
                | "FLOATING_MARKER_NAME"
                | "ADAMS_ID"
                | "LOCATION"
                | "ORIENTATION"
                | "RELATIVE_TO"
                | "COMMENTS" => {}
                _ => self.refuse_unread(statement, argument),
            }
        }
        let id = self.id(index, "ADAMS_ID");
        let frame = if modify && !self.moves(index) {
            Frame::GROUND
        } else {
            self.placed(index)
        };
        if modify {
            match self.find(&name) {
                Some(Entity::Marker(marker)) => {
                    if id.is_some() {
                        self.markers[marker].id = id;
                    }
                    if self.moves(index) {
                        self.markers[marker].frame = frame;
                    }
                }
                _ => {
                    let span = statement.place_of(keyword, keyword.len());
                    self.wrong(
                        "marker_name names no marker the file creates before".into(),
                        span,
                    );
                }
            }
            return;
        }
        let full = self.full(&name);
        let Some((owner, _)) = full.rsplit_once('.') else {
            let span = statement.place_of(keyword, keyword.len());
            self.wrong(
                "a marker's name starts with its part's: .model.part.marker".into(),
                span,
            );
            return;
        };
        let part = match self.find(owner) {
            Some(Entity::Part(part)) => part,
            _ => {
                let span = statement.place_of(keyword, keyword.len());
                self.wrong(
                    format!("the marker's part {owner} is not created before it"),
                    span,
                );
                return;
            }
        };
        self.markers.push(Marker {
            id,
            span: statement.span,
            part,
            frame,
            floating,
        });
        self.name(full, Entity::Marker(self.markers.len() - 1));
    }

    fn transient(&mut self, parameters: &[(String, String)], span: Span) {
        let value = |name: &str| {
            parameters
                .iter()
                .find(|(keyword, _)| keyword.eq_ignore_ascii_case(name))
                .map(|(_, value)| value.as_str())
        };
        let number = |name: &str| value(name).and_then(|text| text.parse::<f64>().ok());
        let end = number("END_TIME").or_else(|| number("DURATION"));
        let steps = number("NUMBER_OF_STEPS")
            .or_else(|| Some(end? / number("STEP_SIZE")?))
            .filter(|steps| steps.is_finite() && *steps >= 1.0);
        match (end, steps) {
            (Some(end), Some(steps)) if end > 0.0 => {
                self.run = Some(RunCommands {
                    end,
                    steps: steps.round() as usize,
                    statics: value("INITIAL_STATIC").is_some_and(|value| value == "YES"),
                    land_on_outputs: false,
                    span,
                });
            }
            _ => self.notes.push((
                "this simulation gives no end time and steps mbexpr reads (end_time and number_of_steps or step_size): give --end and --steps".into(),
                span,
            )),
        }
    }

    /// A `simulation script`'s transient commands, as if given alone; or
    /// its `solver_commands`, a command file's lines (`SIMULATE/STATIC`,
    /// `SIMULATE/DYNAMIC, END=5.0, DTOUT=1.0E-02`), read as an `.acf`.
    fn script(&mut self, index: usize) {
        if let Some(items) = self.items(index, "SOLVER_COMMANDS") {
            let span = items
                .iter()
                .map(|item| item.span)
                .reduce(|first, last| first.to(last))
                .unwrap_or(self.view.statements[index].span);
            let text: Vec<String> = items
                .iter()
                .map(|item| item.text.trim_matches('"').to_string())
                .collect();
            let commands = crate::model::read(&text.join("\n"), crate::model::FileKind::Acf);
            if !commands.problems.is_empty() {
                self.notes.push((
                    "these solver commands are not all commands mbexpr reads: give --end and --steps".into(),
                    span,
                ));
                return;
            }
            match super::commands::run_settings(&commands) {
                Ok(Some(run)) => self.run = Some(RunCommands { span, ..run }),
                Ok(None) => {}
                Err((message, _)) => self.notes.push((
                    format!("these solver commands give no run mbexpr makes ({message}): give --end and --steps"),
                    span,
                )),
            }
            return;
        }
        let Some(items) = self.items(index, "COMMANDS") else {
            return;
        };
        for item in items {
            // Each command as View reads it (abbreviations in full), by the
            // command reader itself.
            let commands = crate::model::read(&item.text, FileKind::Cmd);
            for command in &commands.statements {
                if command.name == "SIMULATION SINGLE_RUN TRANSIENT" {
                    self.transient(&run_parameters(command), item.span);
                }
            }
        }
    }

    /// A feature of a solid (a blend, chamfer or hole: its name is the
    /// solid's and its own), kept with the solid's part: it changes the
    /// solid's volume, which matters where the part's mass comes from its
    /// solids. A feature of a solid the file does not create (a Parasolid
    /// one) is passed over with it.
    fn feature(&mut self, index: usize) {
        if !self.view.statements[index].name.contains(" CREATE ") {
            return;
        }
        let Some(name) = self.object_name(index).map(|name| self.full(&name)) else {
            return;
        };
        let solid = name.rsplit_once('.').map(|(solid, _)| solid.to_string());
        if let Some(Entity::Geometry(geometry)) = solid.and_then(|solid| self.find(&solid))
            && let Some(part) = self.geometries[geometry].part
        {
            self.parts[part].features.push(index);
        }
    }

    fn solid(&mut self, index: usize, shape: &str) {
        let statement = &self.view.statements[index];
        let Some(name) = self.object_name(index).map(|name| self.full(&name)) else {
            return;
        };
        let restated = statement
            .arguments
            .iter()
            .filter(|argument| !argument.keyword.ends_with("_NAME"))
            .all(view_expression);
        if statement.name.contains(" MODIFY ") && restated {
            return;
        }
        let part = match name
            .rsplit_once('.')
            .and_then(|(owner, _)| self.find(owner))
        {
            Some(Entity::Part(part)) => Some(part),
            _ => None,
        };
        if statement.name.contains(" CREATE ") {
            let id = self.id(index, "ADAMS_ID");
            self.geometries.push(Geometry {
                command: index,
                shape: shape.to_string(),
                id,
                part,
                met: false,
            });
            self.name(name, Entity::Geometry(self.geometries.len() - 1));
        }
        // Shapes without volume add no mass; every other is a solid of its
        // part (refused where the part's mass comes from its geometry and
        // mbexpr does not compute the shape's: see `solid_moments`).
        if let Some(part) = part
            && !WIRES.contains(&shape)
        {
            self.parts[part].solids.push(index);
        }
    }

    fn attributes(&mut self, index: usize) {
        let statement = &self.view.statements[index];
        let Some(active) = self.word(index, "ACTIVE") else {
            return;
        };
        if !matches!(active.as_str(), "OFF" | "NO") {
            return;
        }
        let Some(name) = self.object_name(index) else {
            return;
        };
        match self.find(&name) {
            Some(Entity::Element(element)) => {
                self.elements[element].active = false;
                self.notes.push((
                    format!("{} is inactive (active = off): left out", key(&name)),
                    statement.span,
                ));
            }
            Some(Entity::Part(part)) => {
                if self.parts[part].ground {
                    self.refuse(
                        statement,
                        "deactivates the ground part".into(),
                        statement.span,
                    );
                } else {
                    self.parts[part].active = false;
                    self.notes.push((
                        format!(
                            "{} is inactive (active = off): left out, with its markers and the elements on them",
                            name.trim_matches('"')
                        ),
                        statement.span,
                    ));
                }
            }
            Some(Entity::Marker(_)) => self.refuse(
                statement,
                "deactivates a marker, which mbexpr does not: make the elements on it inactive"
                    .into(),
                statement.span,
            ),
            // What the reading passes over (a measure, a graphic, a solid
            // from a file) stays out; a user-defined element made
            // inactive is not refused.
            _ => {
                let name = key(&name);
                for (element, _, active) in &mut self.user_elements {
                    if *element == name {
                        *active = false;
                    }
                }
            }
        }
    }

    fn element(&mut self, index: usize, words: &str, verb: Option<&str>) {
        let statement = &self.view.statements[index];
        let read =
            ELEMENTS.iter().any(|kind| kind.words == words) || constraint_kind(words).is_some();
        let passed_over = PASSED_OVER.iter().any(|over| {
            let spaced = format!("{over} ");
            words == *over || words.starts_with(&spaced) || statement.name.starts_with(&spaced)
        });
        if passed_over && !read {
            return;
        }
        if let Some((_, note)) = NOTED
            .iter()
            .find(|(over, _)| words == *over || words.starts_with(&format!("{over} ")))
        {
            self.notes.push((note.to_string(), statement.span));
            return;
        }
        // What the command language leaves (`model::script`): a loop it
        // could not carry out, a `break` outside any loop.
        let left_by_script = match words {
            "FOR" | "WHILE" => Some(
                "is a loop mbexpr could not carry out: its bounds (or condition) must evaluate to numbers: numbers, arithmetic, variables set before and loop counters, and View's numeric functions (EVAL, RTOI, SQRT ...); a loop over the objects of a type, or reading the model (db_exists ...), is not carried out",
            ),
            "BREAK" | "CONTINUE" => Some(
                "stands outside any loop, so there is nothing for it to leave: take it out, or put it inside the `for` or `while` it is meant to leave",
            ),
            _ => None,
        };
        if let Some(reason) = left_by_script {
            self.refuse(statement, reason.into(), statement.span);
            return;
        }
        let found = ELEMENTS
            .iter()
            .find(|kind| kind.words == words)
            .map(|kind| {
                (
                    kind.statement,
                    kind.flags.to_vec(),
                    kind.name,
                    kind.parameters,
                )
            })
            .or_else(|| {
                let (statement, flag) = constraint_kind(words)?;
                let name = if statement == "JOINT" {
                    "JOINT_NAME"
                } else {
                    "JPRIM_NAME"
                };
                let parameters: &'static [&'static [(&'static str, Becomes)]] =
                    if statement == "JOINT" {
                        JOINT_PARAMETERS
                    } else {
                        &[&TWO_MARKERS]
                    };
                Some((statement, vec![flag], name, parameters))
            });
        let Some((solver, flags, name_keyword, parameters)) = found else {
            let reason = view_vocabulary::ambiguity(&statement.name, None).unwrap_or_else(|| "is not read: mbexpr simulates a View file's parts, markers, joints, joint primitives, general constraints, motions, single-component forces, force and torque vectors, general forces, spring-dampers, bushings, beams, contacts, joint frictions, couplers and gears, gravity, variables, differential equations, function requests and sensors".into());
            self.refuse(statement, reason, statement.span);
            return;
        };
        let Some(verb) = verb else {
            self.refuse(statement, "is not read".into(), statement.span);
            return;
        };
        let Some(name) = self.word(index, name_keyword) else {
            let span = statement.span;
            self.wrong(
                format!("{} is missing", name_keyword.to_ascii_lowercase()),
                span,
            );
            return;
        };
        let element = if verb == "CREATE" {
            self.elements.push(Element {
                statement: solver,
                flags,
                parameters,
                id: None,
                span: statement.span,
                given: Vec::new(),
                active: true,
                name: name.clone(),
            });
            let element = self.elements.len() - 1;
            let full = self.full(&name);
            self.name(full, Entity::Element(element));
            element
        } else {
            match self.find(&name) {
                Some(Entity::Element(element)) if self.elements[element].statement == solver => {
                    element
                }
                _ => {
                    let span = statement.place_of(name_keyword, name_keyword.len());
                    if let Some(reason) = self.inside_instance(&name) {
                        self.refuse(statement, reason, span);
                        return;
                    }
                    self.wrong(
                        format!(
                            "{} names no {} the file creates before",
                            name_keyword.to_ascii_lowercase(),
                            words.to_ascii_lowercase()
                        ),
                        span,
                    );
                    return;
                }
            }
        };
        if let Some(id) = self.id(index, "ADAMS_ID") {
            self.elements[element].id = Some(id);
        }
        for (position, argument) in statement.arguments.iter().enumerate() {
            let keyword = argument.keyword.as_str();
            if keyword == name_keyword || matches!(keyword, "ADAMS_ID" | "COMMENTS" | "NEW_NAME") {
                continue;
            }
            if becomes(parameters, keyword).is_none() {
                // A measure's parameters count only where a function reads
                // it, and are checked there.
                if solver != MEASURE {
                    self.refuse_unread(statement, argument);
                }
                continue;
            }
            let known = self.elements[element]
                .given
                .iter()
                .any(|(name, _, _)| name == keyword);
            if view_expression(argument) {
                // A View expression restates the value the create command
                // wrote evaluated; one with nothing before cannot be read.
                if !known {
                    self.wrong(
                        format!(
                            "{}: a View expression mbexpr could not evaluate (a value with its unit, a function of the model, a name no variable before has), and no command before gives the value: give the number",
                            keyword.to_ascii_lowercase()
                        ),
                        argument.span,
                    );
                }
                continue;
            }
            let given = &mut self.elements[element].given;
            given.retain(|(name, _, _)| name != keyword);
            given.push((argument.keyword.clone(), index, position));
        }
    }

    /// The ids of every object, given or the next free of its kind.
    fn assign_ids(&mut self) {
        let mut taken: HashMap<&'static str, HashSet<u64>> = HashMap::new();
        let kind = |part: &Part| {
            if part.point_mass {
                "POINT_MASS"
            } else {
                "PART"
            }
        };
        for part in &self.parts {
            taken.entry(kind(part)).or_default().extend(part.id);
        }
        for marker in &self.markers {
            taken.entry("MARKER").or_default().extend(marker.id);
        }
        for element in &self.elements {
            taken
                .entry(element.statement)
                .or_default()
                .extend(element.id);
        }
        for geometry in &self.geometries {
            taken.entry("GRAPHICS").or_default().extend(geometry.id);
        }
        // The smallest free id only grows as ids are taken, so each kind's
        // search starts where its last one ended (linear in the ids).
        let mut searched_from: HashMap<&'static str, u64> = HashMap::new();
        let mut next = |kind: &'static str| {
            let ids = taken.entry(kind).or_default();
            let from = searched_from.entry(kind).or_insert(1);
            let id = (*from..).find(|id| !ids.contains(id)).unwrap_or(*from);
            ids.insert(id);
            *from = id + 1;
            id
        };
        // The ground first, so that it takes 1 when it is free.
        let mut order: Vec<usize> = (0..self.parts.len()).collect();
        order.sort_by_key(|&part| !self.parts[part].ground);
        for part in order {
            if self.parts[part].id.is_none() {
                self.parts[part].id = Some(next(kind(&self.parts[part])));
            }
        }
        for marker in &mut self.markers {
            if marker.id.is_none() {
                marker.id = Some(next("MARKER"));
            }
        }
        for element in &mut self.elements {
            if element.id.is_none() {
                element.id = Some(next(element.statement));
            }
        }
        for geometry in &mut self.geometries {
            if geometry.id.is_none() {
                geometry.id = Some(next("GRAPHICS"));
            }
        }
    }

    /// Makes inactive every element that names a marker or solid on an
    /// inactive part, or a joint made inactive so (in file order), as View
    /// does with what depends on an inactive part.
    fn leave_out_on_inactive_parts(&mut self) {
        if self.parts.iter().all(|part| part.active) {
            return;
        }
        for element in 0..self.elements.len() {
            if !self.elements[element].active {
                continue;
            }
            let parameters = self.elements[element].parameters;
            let mut on_inactive = false;
            for (keyword, index, _) in &self.elements[element].given {
                let Some(becomes) = becomes(parameters, keyword) else {
                    continue;
                };
                let names = self.names(*index, keyword);
                for name in names {
                    on_inactive |= match (becomes, self.find(&name)) {
                        (Becomes::Marker(_), Some(Entity::Marker(marker))) => {
                            !self.parts[self.markers[marker].part].active
                        }
                        (Becomes::FloatingOn(_), Some(Entity::Part(part))) => {
                            !self.parts[part].active
                        }
                        (Becomes::Solids(_), Some(Entity::Geometry(geometry))) => self.geometries
                            [geometry]
                            .part
                            .is_some_and(|part| !self.parts[part].active),
                        (Becomes::Object(_) | Becomes::Joints(_), Some(Entity::Element(joint))) => {
                            !self.elements[joint].active
                        }
                        _ => false,
                    };
                }
            }
            if on_inactive {
                self.elements[element].active = false;
                let span = self.elements[element].span;
                self.notes
                    .push(("left out: it acts on an inactive part".into(), span));
            }
        }
    }

    /// A new marker on `part` at `frame`, with the next free id.
    fn new_marker(&mut self, part: usize, frame: Frame, floating: bool, span: Span) -> u64 {
        let id = self
            .markers
            .iter()
            .filter_map(|marker| marker.id)
            .max()
            .unwrap_or(0)
            + 1;
        self.markers.push(Marker {
            id: Some(id),
            span,
            part,
            frame,
            floating,
        });
        id
    }

    /// The marker whose axes the frame `keyword` of command `index` names
    /// are: a marker, a point's marker, a part's (a marker made at its
    /// frame), or ground's (0) for the ground part and the model.
    fn frame_marker(&mut self, index: usize, keyword: &str) -> Option<u64> {
        let name = self.word(index, keyword)?;
        match self.find(&name) {
            Some(Entity::Part(part)) if self.parts[part].ground => Some(0),
            Some(Entity::Model) => Some(0),
            Some(Entity::Part(part)) => {
                if self.parts[part].frame_marker.is_none() {
                    let (frame, span) = (self.parts[part].frame, self.parts[part].span);
                    self.parts[part].frame_marker = Some(self.new_marker(part, frame, false, span));
                }
                self.parts[part].frame_marker
            }
            _ => self.marker_id(index, keyword),
        }
    }

    fn marker_id(&mut self, index: usize, keyword: &str) -> Option<u64> {
        let name = self.word(index, keyword)?;
        match self.find(&name) {
            Some(Entity::Marker(marker)) => self.markers[marker].id,
            Some(Entity::Point(point)) => {
                if self.points[point].marker.is_none() {
                    let Point {
                        part, frame, span, ..
                    } = self.points[point];
                    self.points[point].marker = Some(self.new_marker(part, frame, false, span));
                }
                self.points[point].marker
            }
            _ => {
                let span = self.view.statements[index].place_of(keyword, keyword.len());
                self.wrong(
                    format!(
                        "{} names no marker the file creates",
                        keyword.to_ascii_lowercase()
                    ),
                    span,
                );
                None
            }
        }
    }
}

/// A transient run command's parameters, each keyword with its first
/// value as a key.
fn run_parameters(statement: &Statement) -> Vec<(String, String)> {
    statement
        .arguments
        .iter()
        .filter_map(|argument| match &argument.value {
            Value::List(items) => items
                .first()
                .map(|item| (argument.keyword.to_string(), key(&item.text))),
            _ => None,
        })
        .collect()
}

/// Whether an argument holds a View expression: a value in brackets
/// (`(20g)`, `(.model.DV_1)`, `(LOC_RELATIVE_TO({0, 0, 0}, .model.ground))`),
/// which View evaluates and mbexpr does not.
fn view_expression(argument: &Argument) -> bool {
    match &argument.value {
        Value::List(items) => items
            .iter()
            .any(|item| item.text.trim_start().starts_with('(')),
        Value::Flag | Value::Expression { .. } => false,
    }
}

/// A sequence of three turns that gives orientations (View's
/// `orientation_type`): about the axes `axes` (0 for x, 1 for y, 2 for z)
/// in turn, each about the axis as the turns before left it (`body`), or
/// about ground's (`space`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Orientations {
    /// Each turn about the axes the turns before left (a body sequence).
    body: bool,
    /// The axes of the three turns, in order.
    axes: [usize; 3],
}

impl Orientations {
    /// Body 3-1-3, View's default and the solver's.
    const BODY_313: Orientations = Orientations {
        body: true,
        axes: [2, 0, 2],
    };

    /// The sequence View names `name` (`BODY313`, `SPACE123`): `BODY` or
    /// `SPACE` and three axes, no axis twice in a row.
    fn named(name: &str) -> Option<Orientations> {
        let (body, digits) = match name.strip_prefix("BODY") {
            Some(digits) => (true, digits),
            None => (false, name.strip_prefix("SPACE")?),
        };
        let axes: Vec<usize> = digits
            .chars()
            .map(|digit| match digit {
                '1' => Some(0),
                '2' => Some(1),
                '3' => Some(2),
                _ => None,
            })
            .collect::<Option<_>>()?;
        let [a, b, c] = axes[..] else { return None };
        (a != b && b != c).then_some(Orientations {
            body,
            axes: [a, b, c],
        })
    }

    /// The axes (columns, in the frame the angles are given in) of the
    /// orientation `angles` (radians): a body sequence turns by `R₁ R₂
    /// R₃`, a space one by `R₃ R₂ R₁`.
    fn axes(self, angles: [f64; 3]) -> Matrix3<f64> {
        let turns = [0, 1, 2].map(|k| {
            let axis = Unit::new_unchecked(Vector3::ith(self.axes[k], 1.0));
            Rotation3::from_axis_angle(&axis, angles[k])
        });
        let [first, second, third] = turns;
        if self.body {
            (first * second * third).into_inner()
        } else {
            (third * second * first).into_inner()
        }
    }
}
