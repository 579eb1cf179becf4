//! The solver statements the reader writes: parts, markers, elements
//! and the GRAPHICS of contacts' solids, and functions with their names
//! turned into ids.

use std::collections::HashSet;
use std::f64::consts::PI;

use super::elements::{Becomes, MEASURE, becomes};
use super::library::{LibrarySpring, spring_statement};
use super::{Entity, Frame, Reader};
use crate::check::{Argument as TreeArgument, Checked, NodeKind, Reference, visit};
use crate::model::{Argument, Embedded, GENERAL_MOTION, Statement, Value, ValueItem};
use crate::span::Span;

/// How deep function measures may read one another (each level a
/// recursion of the reader).
const MEASURE_DEPTH: usize = 32;

impl Reader<'_> {
    /// The solver statements.
    pub(super) fn write(&mut self) -> Vec<Statement> {
        self.assign_ids();
        let (springs, spring_variables) = self.write_user_elements();
        let mut statements = Vec::new();
        let mut units = new_statement("UNITS", None, self.units_span);
        for (kind, unit) in self.units {
            words_argument(&mut units, kind, &[unit], self.units_span);
        }
        statements.push(units);
        self.leave_out_on_inactive_parts();
        let mut parts = Vec::new();
        for part in 0..self.parts.len() {
            if !self.parts[part].active {
                continue;
            }
            if let Some(statement) = self.write_part(part) {
                parts.push(statement);
            }
        }
        statements.extend(parts);
        let mut elements = Vec::new();
        for element in 0..self.elements.len() {
            if self.elements[element].active
                && self.elements[element].statement != MEASURE
                && let Some(statement) = self.write_element(element)
            {
                elements.push(statement);
            }
        }
        elements.extend(springs);
        elements.extend(self.write_measures(spring_variables));
        for geometry in 0..self.geometries.len() {
            if self.geometries[geometry].met
                && let Some(statement) = self.write_graphic(geometry)
            {
                elements.push(statement);
            }
        }
        // Markers last: writing the parts and elements makes some.
        for marker in &self.markers {
            let part = &self.parts[marker.part];
            if !part.active {
                continue;
            }
            let mut statement = new_statement("MARKER", marker.id, marker.span);
            let owner = if part.point_mass {
                "POINT_MASS"
            } else {
                "PART"
            };
            ids_argument(&mut statement, owner, part.id.unwrap_or(0), marker.span);
            if marker.floating {
                flag_argument(&mut statement, "FLOATING", marker.span);
            } else {
                let local = part.frame.seen(&marker.frame);
                place_arguments(&mut statement, ["QP", "ZP", "XP"], &local, marker.span);
            }
            statements.push(statement);
        }
        statements.extend(elements);
        statements
    }

    fn write_part(&mut self, part: usize) -> Option<Statement> {
        let span = self.parts[part].span;
        let kind = if self.parts[part].point_mass {
            "POINT_MASS"
        } else {
            "PART"
        };
        let mut statement = new_statement(kind, self.parts[part].id, span);
        if self.parts[part].ground {
            flag_argument(&mut statement, "GROUND", span);
            return Some(statement);
        }
        let frame = self.parts[part].frame;
        place_arguments(&mut statement, ["QG", "ZG", "XG"], &frame, span);
        if let Some((exact, at)) = &self.parts[part].exact
            && !exact.is_empty()
        {
            words_argument(&mut statement, "EXACT", &[&exact.join(":")], *at);
        }
        if let Some(index) = self.parts[part].mass {
            self.mass_properties(part, index, &mut statement);
        }
        if let Some(index) = self.parts[part].velocity {
            self.velocities(index, &mut statement);
        }
        Some(statement)
    }

    fn velocities(&mut self, index: usize, statement: &mut Statement) {
        let command = &self.view.statements[index];
        for argument in &command.arguments {
            let keyword = argument.keyword.as_str();
            match keyword {
                "PART_NAME" | "POINT_MASS_NAME" => {}
                "VX" | "VY" | "VZ" | "WX" | "WY" | "WZ" => {
                    let angular = keyword.starts_with('W');
                    if let Some(values) = self.numbers(index, keyword, angular) {
                        numbers_argument(statement, keyword, &values, argument.span);
                    }
                }
                "VM" | "WM" => {
                    if let Some(id) = self.marker_id(index, keyword) {
                        ids_argument(statement, keyword, id, argument.span);
                    }
                }
                "GROUND" | "VX_GROUND" => {}
                _ => self.refuse_unread(command, argument),
            }
        }
    }

    fn write_element(&mut self, element: usize) -> Option<Statement> {
        let (solver, span, id) = {
            let element = &self.elements[element];
            (element.statement, element.span, element.id)
        };
        let id = if solver == "ACCGRAV" { None } else { id };
        let mut statement = new_statement(solver, id, span);
        for flag in self.elements[element].flags.clone() {
            flag_argument(&mut statement, flag, span);
        }
        let rotational = self.elements[element]
            .given
            .iter()
            .any(|(keyword, index, _)| {
                matches!(keyword.as_str(), "TYPE_OF_FREEDOM" | "AXIS")
                    && matches!(
                        self.word(*index, keyword).as_deref(),
                        Some("ROTATIONAL" | "B1" | "B2" | "B3")
                    )
            });
        let given = |name: &str| {
            self.elements[element]
                .given
                .iter()
                .any(|(keyword, _, _)| keyword == name)
        };
        if solver == "CONTACT" && !given("STIFFNESS") && given("RESTITUTION_COEFFICIENT") {
            self.refuse(
                &self.view.statements[self.elements[element].given[0].1],
                "is a restitution (POISSON) contact, which mbexpr does not simulate: give the impact law's stiffness, damping, exponent and dmax".into(),
                span,
            );
            return None;
        }
        let parameters = self.elements[element].parameters;
        // A joint's initial conditions, [translation, rotation] ×
        // [displacement, velocity], with the place of the first given.
        let mut initials = [[None; 2]; 2];
        let mut initials_span = [None; 2];
        // A friction's inputs, each on or off, with the place of the first.
        let mut inputs: Vec<&str> = Vec::new();
        let mut inputs_off = false;
        let mut inputs_span = None;
        for (keyword, index, position) in self.elements[element].given.clone() {
            let argument = &self.view.statements[index].arguments[position];
            let Some(becomes) = becomes(parameters, &keyword) else {
                continue;
            };
            let argument_span = argument.span;
            match becomes {
                Becomes::Marker(solver_keyword) => {
                    if let Some(id) = self.marker_id(index, &keyword) {
                        ids_argument(&mut statement, solver_keyword, id, argument_span);
                    }
                }
                Becomes::FloatingOn(solver_keyword) => {
                    if let Some(part) = self.part_named(index, &keyword) {
                        let frame = self.parts[part].frame;
                        let id = self.new_marker(part, frame, true, argument_span);
                        ids_argument(&mut statement, solver_keyword, id, argument_span);
                    }
                }
                Becomes::Object(solver_keyword) => {
                    let name = self.word(index, &keyword).unwrap_or_default();
                    match self.find(&name) {
                        Some(Entity::Element(target))
                            if self.elements[target].statement == solver_keyword =>
                        {
                            let target_id = self.elements[target].id.unwrap_or(0);
                            ids_argument(&mut statement, solver_keyword, target_id, argument_span);
                        }
                        _ => self.wrong(
                            format!(
                                "{} names no {} the file creates",
                                keyword.to_ascii_lowercase(),
                                solver_keyword.to_ascii_lowercase()
                            ),
                            argument_span,
                        ),
                    }
                }
                Becomes::Numbers(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, false) {
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::Angles(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, true) {
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::Initial(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, rotational) {
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::JointInitial { rotation, velocity } => {
                    if let Some(values) = self.numbers(index, &keyword, rotation) {
                        match values.as_slice() {
                            [value] => {
                                initials[usize::from(rotation)][usize::from(velocity)] =
                                    Some(*value);
                                initials_span[usize::from(rotation)].get_or_insert(argument_span);
                            }
                            _ => self.wrong(
                                format!("{} is one number", keyword.to_ascii_lowercase()),
                                argument_span,
                            ),
                        }
                    }
                }
                Becomes::Named(solver_keyword, names) => {
                    if let Some(solver_word) = self.one_of(index, &keyword, names, argument_span) {
                        words_argument(
                            &mut statement,
                            solver_keyword,
                            &[solver_word],
                            argument_span,
                        );
                    }
                }
                Becomes::SwitchTo(solver_keyword, solver_word) => {
                    if self.switch(index, &keyword, argument_span) == Some(true) {
                        words_argument(
                            &mut statement,
                            solver_keyword,
                            &[solver_word],
                            argument_span,
                        );
                    }
                }
                Becomes::Input(input) => {
                    if let Some(on) = self.switch(index, &keyword, argument_span) {
                        inputs_span.get_or_insert(argument_span);
                        if on {
                            inputs.push(input);
                        } else {
                            inputs_off = true;
                        }
                    }
                }
                Becomes::PerAngle(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, false) {
                        let scale = if self.degrees { 180.0 / PI } else { 1.0 };
                        let values: Vec<f64> = values.iter().map(|value| value * scale).collect();
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::OptionalFunction(_) if matches!(&argument.value, Value::Expression { text, .. } if text.text.trim().is_empty()) =>
                    {}
                Becomes::Function(solver_keyword) | Becomes::OptionalFunction(solver_keyword) => {
                    if let Some(text) = self.function(index, position) {
                        statement.arguments.push(Argument {
                            keyword: solver_keyword.into(),
                            keyword_span: argument.keyword_span,
                            span: argument_span,
                            value: Value::Expression {
                                text,
                                span: argument_span,
                            },
                        });
                    }
                }
                Becomes::Choice(choices) => {
                    if let Some(solver_keyword) =
                        self.one_of(index, &keyword, choices, argument_span)
                    {
                        flag_argument(&mut statement, solver_keyword, argument_span);
                    }
                }
                Becomes::Word(solver_keyword) => {
                    let word = self.word(index, &keyword).unwrap_or_default();
                    words_argument(&mut statement, solver_keyword, &[&word], argument_span);
                }
                Becomes::Solids(solver_keyword) => {
                    let names = self.names(index, &keyword);
                    let mut ids = Vec::new();
                    for name in names {
                        match self.find(&name) {
                            Some(Entity::Geometry(geometry)) => {
                                self.geometries[geometry].met = true;
                                ids.push(self.geometries[geometry].id.unwrap_or(0).to_string());
                            }
                            _ => self.refuse(
                                &self.view.statements[index],
                                format!(
                                    "meets {name}, which is no solid this file creates (solids read from a file by `file parasolid read` are not read)"
                                ),
                                argument_span,
                            ),
                        }
                    }
                    let ids: Vec<&str> = ids.iter().map(String::as_str).collect();
                    words_argument(&mut statement, solver_keyword, &ids, argument_span);
                }
                Becomes::Joints(solver_keyword) => {
                    let names = self.names(index, &keyword);
                    let mut ids = Vec::new();
                    for name in names {
                        match self.find(&name) {
                            Some(Entity::Element(joint))
                                if self.elements[joint].statement == "JOINT" =>
                            {
                                ids.push(self.elements[joint].id.unwrap_or(0).to_string());
                            }
                            _ => self.wrong(
                                format!("{name} is no joint the file creates"),
                                argument_span,
                            ),
                        }
                    }
                    let ids: Vec<&str> = ids.iter().map(String::as_str).collect();
                    words_argument(&mut statement, solver_keyword, &ids, argument_span);
                }
                Becomes::Freedoms(solver_keyword) => {
                    let word = self.word(index, &keyword).unwrap_or_default();
                    let freedoms: Option<Vec<&str>> = word
                        .split('_')
                        .map(|freedom| match freedom {
                            "TRANS" | "TRANSLATIONAL" => Some("T"),
                            "ROT" | "ROTATIONAL" => Some("R"),
                            _ => None,
                        })
                        .collect();
                    match freedoms {
                        Some(freedoms) => {
                            let value = freedoms.join(":");
                            words_argument(
                                &mut statement,
                                solver_keyword,
                                &[&value],
                                argument_span,
                            );
                        }
                        None => self.wrong(
                            format!(
                                "{} is the joints' freedoms joined by _ (rot_rot, trans_rot ...)",
                                keyword.to_ascii_lowercase()
                            ),
                            argument_span,
                        ),
                    }
                }
                Becomes::Switch(solver_keyword) => {
                    if self.switch(index, &keyword, argument_span) == Some(true) {
                        flag_argument(&mut statement, solver_keyword, argument_span);
                    }
                }
                Becomes::Nothing => {}
            }
        }
        // INPUTS lists the loads left on when one is turned off; else it is
        // left out, and the friction reads every load its joint has.
        if let Some(span) = inputs_span
            && inputs_off
        {
            let words = if inputs.is_empty() {
                vec!["NONE"]
            } else {
                inputs
            };
            words_argument(&mut statement, "INPUTS", &words, span);
        }
        self.write_initials(&mut statement, initials, initials_span);
        Some(statement)
    }

    /// The solver's word for the View word parameter `keyword` of command
    /// `index` gives among `choices` (View's word, the solver's); another
    /// word is wrong at `span`.
    fn one_of(
        &mut self,
        index: usize,
        keyword: &str,
        choices: &[(&'static str, &'static str)],
        span: Span,
    ) -> Option<&'static str> {
        let word = self.word(index, keyword).unwrap_or_default();
        let found = choices
            .iter()
            .find(|(view, _)| *view == word)
            .map(|&(_, solver)| solver);
        if found.is_none() {
            let listed: Vec<String> = choices
                .iter()
                .map(|(view, _)| view.to_ascii_lowercase())
                .collect();
            self.wrong(
                format!(
                    "{} is one of {}",
                    keyword.to_ascii_lowercase(),
                    listed.join(", ")
                ),
                span,
            );
        }
        found
    }

    /// A joint's initial conditions as its IC (a revolute joint's rotation,
    /// a translational one's translation) or a cylindrical joint's ICROT
    /// and ICTRAN: the velocity, then the displacement, as Adams reads
    /// them; a displacement alone leaves the velocity empty.
    fn write_initials(
        &mut self,
        statement: &mut Statement,
        initials: [[Option<f64>; 2]; 2],
        spans: [Option<Span>; 2],
    ) {
        let cylindrical = statement
            .arguments
            .iter()
            .any(|argument| argument.keyword == "CYLINDRICAL");
        for (rotation, [displacement, velocity]) in initials.into_iter().enumerate() {
            let Some(span) = spans[rotation] else {
                continue;
            };
            let keyword = match (cylindrical, rotation == 1) {
                (false, _) => "IC",
                (true, true) => "ICROT",
                (true, false) => "ICTRAN",
            };
            let text =
                |value: Option<f64>| value.map_or_else(String::new, |value| format!("{value:?}"));
            // The velocity first, as Adams reads a joint's IC.
            let texts = match displacement {
                Some(_) => vec![text(velocity), text(displacement)],
                None => vec![text(velocity)],
            };
            list_argument(statement, keyword, texts, span);
        }
    }

    /// The GRAPHICS statement of a geometry a contact meets: the solids a
    /// CONTACT reads (a sphere, a block, a cylinder, a frustum, a plane);
    /// another shape is refused at its command.
    fn write_graphic(&mut self, geometry: usize) -> Option<Statement> {
        let index = self.geometries[geometry].command;
        let shape = self.geometries[geometry].shape.clone();
        let span = self.view.statements[index].span;
        let mut statement = new_statement("GRAPHICS", self.geometries[geometry].id, span);
        let marker = |reader: &mut Self, view: &str, solver: &str, statement: &mut Statement| {
            if let Some(id) = reader.marker_id(index, view) {
                ids_argument(statement, solver, id, span);
            }
        };
        let numbers = |reader: &mut Self, view: &str, solver: &str, statement: &mut Statement| {
            if let Some(values) = reader.numbers(index, view, false) {
                numbers_argument(statement, solver, &values, span);
            }
        };
        match shape.as_str() {
            "ELLIPSOID" => {
                flag_argument(&mut statement, "ELLIPSOID", span);
                marker(self, "CENTER_MARKER", "CM", &mut statement);
                for (view, solver) in [
                    ("X_SCALE_FACTOR", "XSCALE"),
                    ("Y_SCALE_FACTOR", "YSCALE"),
                    ("Z_SCALE_FACTOR", "ZSCALE"),
                ] {
                    numbers(self, view, solver, &mut statement);
                }
            }
            "BLOCK" => {
                flag_argument(&mut statement, "BOX", span);
                marker(self, "CORNER_MARKER", "CORNER", &mut statement);
                if let Some(corner) = self.numbers(index, "DIAG_CORNER_COORDS", false)
                    && let [x, y, z] = corner[..]
                {
                    for (keyword, value) in [("X", x), ("Y", y), ("Z", z)] {
                        numbers_argument(&mut statement, keyword, &[value], span);
                    }
                }
            }
            "CYLINDER" | "FRUSTUM" => {
                flag_argument(&mut statement, &shape, span);
                marker(self, "CENTER_MARKER", "CM", &mut statement);
                numbers(self, "LENGTH", "LENGTH", &mut statement);
                if shape == "CYLINDER" {
                    numbers(self, "RADIUS", "RADIUS", &mut statement);
                } else {
                    numbers(self, "TOP_RADIUS", "TOP", &mut statement);
                    numbers(self, "BOTTOM_RADIUS", "BOTTOM", &mut statement);
                }
                let extent = self
                    .numbers(index, "ANGLE_EXTENT", true)
                    .and_then(|values| values.first().copied())
                    .unwrap_or(2.0 * PI);
                if (extent.abs() - 2.0 * PI).abs() > 1e-9 {
                    numbers_argument(&mut statement, "RANGLE", &[extent], span);
                }
            }
            "PLANE" => {
                flag_argument(&mut statement, "PLANE", span);
                marker(self, "REF_MARKER_NAME", "RM", &mut statement);
            }
            _ => {
                let command = &self.view.statements[index];
                self.refuse(
                    command,
                    "is a solid a contact meets that mbexpr does not: it meets spheres (ellipsoids of equal scales), blocks, cylinders, frustums and planes".into(),
                    span,
                );
                return None;
            }
        }
        Some(statement)
    }

    /// The function of argument `position` of command `index`, its names
    /// turned into ids; `None` (with the reason) when it cannot be.
    fn function(&mut self, index: usize, position: usize) -> Option<Embedded> {
        let statement = &self.view.statements[index];
        let argument = &statement.arguments[position];
        let Value::Expression { text, span } = &argument.value else {
            return None;
        };
        if text.text.trim().is_empty() {
            // View's "no function yet": the element is refused if no later
            // command gives one.
            self.wrong(
                format!(
                    "{} is empty, and no later command gives it: an element needs its function",
                    argument.keyword.to_ascii_lowercase()
                ),
                *span,
            );
            return None;
        }
        let tree = *self.trees.get(&(index, argument.keyword.clone()))?;
        let text = text.clone();
        self.solver_function(tree, &text)
    }

    /// The solver form of a View function `text` (checked as `tree`): its
    /// names replaced by ids, design variables by their values, function
    /// measures by their functions; what it names that is none of these
    /// is wrong at its place.
    pub(super) fn solver_function(&mut self, tree: &Checked, text: &Embedded) -> Option<Embedded> {
        let mut replacements = Vec::new();
        let mut unknown = Vec::new();
        visit(&tree.root, &mut |node| match &node.kind {
            NodeKind::Variable(name) => unknown.push((name.to_string(), node.span)),
            NodeKind::Call(_, arguments) => {
                for argument in arguments {
                    if let TreeArgument::Marker(Reference::Name(name), span)
                    | TreeArgument::Object(Reference::Name(name), span) = argument
                    {
                        replacements.push((*span, name.clone()));
                    }
                }
            }
            _ => {}
        });
        let mut ids = Vec::new();
        for (name, at) in unknown {
            match self.find(&name) {
                Some(Entity::Design(design)) => {
                    ids.push((at, format!("({:?})", self.designs[design])));
                }
                Some(Entity::Element(measure))
                    if self.elements[measure].statement == MEASURE
                        && !self.reading.contains(&measure)
                        && self.reading.len() < MEASURE_DEPTH =>
                {
                    match self.measure_function(measure) {
                        Some(measured) => ids.push((at, format!("({})", measured.text))),
                        // A kinematic measure says what it lacks.
                        None if !self.elements[measure].flags.is_empty() => {}
                        None => self.wrong(
                            format!("{name}: the measure has no function mbexpr reads"),
                            text.file_span(at),
                        ),
                    }
                }
                Some(Entity::Element(measure)) if self.elements[measure].statement == MEASURE => {
                    self.wrong(
                        format!(
                            "{name}: function measures read one another in a loop, or {MEASURE_DEPTH} deep"
                        ),
                        text.file_span(at),
                    );
                }
                _ => {
                    let message = self.inside_instance(&name).unwrap_or_else(|| format!(
                        "{name} is a View object mbexpr does not evaluate in a function (it reads design variables and function measures): give its value"
                    ));
                    self.wrong(message, text.file_span(at));
                }
            }
        }
        for (at, name) in replacements {
            let id = match self.find(&name) {
                Some(Entity::Marker(marker)) => self.markers[marker].id,
                Some(Entity::Part(part)) => self.parts[part].id,
                Some(Entity::Element(element)) => self.elements[element].id,
                Some(Entity::Written(id)) => Some(id),
                _ => None,
            };
            match id {
                Some(id) => ids.push((at, id.to_string())),
                None => {
                    let message = self.inside_instance(&name).unwrap_or_else(|| {
                        format!("{name} is no marker, part or element the file creates")
                    });
                    self.wrong(message, text.file_span(at));
                }
            }
        }
        ids.sort_by_key(|(at, _)| at.start);
        Some(text.replaced(&ids))
    }
}

/// The solver functions of View's kinematic characteristics: the
/// characteristic, then the function of a component along an axis (`DX`,
/// with `{}` for the axis) and of the magnitude, and whether they take
/// the frame the time derivative is in.
const CHARACTERISTICS: [(&str, &str, &str, bool); 5] = [
    ("TRANSLATIONAL_DISPLACEMENT", "D{}", "DM", false),
    ("TRANSLATIONAL_VELOCITY", "V{}", "VM", true),
    ("TRANSLATIONAL_ACCELERATION", "ACC{}", "ACCM", true),
    ("ANGULAR_VELOCITY", "W{}", "WM", false),
    ("ANGULAR_ACCELERATION", "WDT{}", "WDTM", true),
];

/// A part's characteristics (`measure create object` of a part): those of
/// its centre-of-mass marker.
const CENTRE_CHARACTERISTICS: [(&str, &str); 5] = [
    ("CM_POSITION", "TRANSLATIONAL_DISPLACEMENT"),
    ("CM_VELOCITY", "TRANSLATIONAL_VELOCITY"),
    ("CM_ACCELERATION", "TRANSLATIONAL_ACCELERATION"),
    ("CM_ANGULAR_VELOCITY", "ANGULAR_VELOCITY"),
    ("CM_ANGULAR_ACCELERATION", "ANGULAR_ACCELERATION"),
];

impl Reader<'_> {
    /// The ids no element of the solver statement `kind` has, smallest
    /// first (View's export numbers what it makes so).
    fn free_ids(&self, kind: &str) -> impl Iterator<Item = u64> + use<> {
        let taken: HashSet<u64> = self
            .elements
            .iter()
            .filter(|element| element.statement == kind)
            .filter_map(|element| element.id)
            .collect();
        (1..).filter(move |id| !taken.contains(id))
    }

    /// The active user-defined elements: each library spring's SFORCE
    /// (the smallest ids no SFORCE has, in order) and its VARIABLEs' names
    /// and functions, each general motion's MOTIONs (the smallest ids no
    /// MOTION has); any other is refused.
    fn write_user_elements(&mut self) -> (Vec<Statement>, Vec<(String, String, Span)>) {
        let mut free = self.free_ids("SFORCE");
        let mut free_motions = self.free_ids("MOTION");
        let mut springs = Vec::new();
        let mut variables = Vec::new();
        for (name, index, active) in self.user_elements.clone() {
            if !active {
                continue;
            }
            let command = &self.view.statements[index];
            let kind = self
                .instances
                .iter()
                .find(|(instance, _)| *instance == name)
                .and_then(|(_, definition)| LibrarySpring::of_definition(definition));
            let general_motion = self
                .instances
                .iter()
                .any(|(instance, definition)| *instance == name && definition == GENERAL_MOTION);
            if general_motion {
                match self.general_motion(&name, index, &mut free_motions) {
                    Ok(motions) => springs.extend(motions),
                    Err((reason, place)) => {
                        let at = &self.view.statements[place.unwrap_or(index)];
                        self.refuse(at, format!("{name} {reason}"), at.span);
                    }
                }
                continue;
            }
            let Some(kind) = kind else {
                let definition = self
                    .instances
                    .iter()
                    .find(|(instance, _)| *instance == name)
                    .map(|(_, definition)| definition.as_str())
                    .unwrap_or_default();
                let reason = if definition.contains(".CONSTRAINTS.") {
                    "is a user-defined constraint (a View library element: a general motion drives the components of one marker's motion relative to another), which mbexpr does not read: write each driven component as a motion between the markers (constraint create motion_generator with i_marker_name, j_marker_name and axis)".to_string()
                } else if definition.contains(".FORCES.") {
                    "is a user-defined force (a View library element other than a spring or a torsion spring), which mbexpr does not read: write it as a force element".to_string()
                } else {
                    format!(
                        "is an instance of the user-defined element {}, whose definition makes the parts, constraints or forces it stands for, which mbexpr does not read: write them as View commands",
                        definition.to_ascii_lowercase()
                    )
                };
                self.refuse(command, reason, command.span);
                continue;
            };
            match self.library_spring(&name, kind) {
                Ok(spring) => {
                    let id = free.next().unwrap_or(u64::MAX);
                    springs.push(spring_statement(&spring, kind, id, command.span));
                    for (variable, function) in spring.variables {
                        let function = function.replace("{id}", &id.to_string());
                        variables.push((variable, function, command.span));
                    }
                }
                Err((reason, place)) => {
                    let at = &self.view.statements[place.unwrap_or(index)];
                    self.refuse(at, format!("{name} {reason}"), at.span);
                }
            }
        }
        (springs, variables)
    }

    /// The measures as VARIABLEs, as View has the solver compute them (a
    /// column each in the run's rows), numbered by the ids the file's
    /// variables leave free: each active function or kinematic measure
    /// mbexpr reads. One it does not read (a part's kinetic energy, a
    /// point's total force ...) is left out with a note, not refused: only
    /// a function that reads it needs it. The library springs' VARIABLEs
    /// (`first`: each name, function and place) come before them.
    fn write_measures(&mut self, first: Vec<(String, String, Span)>) -> Vec<Statement> {
        // Each measure takes the smallest id no VARIABLE has, in order, as
        // View's export numbers them (variables 1-4 and 8-18 leave 5, 6, 7
        // to the first three measures and 19 on to the rest).
        let mut free = self.free_ids("VARIABLE");
        let mut variables = Vec::new();
        let mut written = Vec::new();
        let mut unread = Vec::new();
        // The next free id's VARIABLE of `function`, noted as `name`'s.
        let mut variable = |name: &str, function: Embedded, span: Span| {
            let next = free.next().unwrap_or(u64::MAX);
            let mut statement = new_statement("VARIABLE", Some(next), span);
            function_argument(&mut statement, function, span);
            variables.push(statement);
            written.push(format!("VARIABLE/{next} = {name}"));
        };
        for (name, function, span) in first {
            variable(&name, Embedded::pinned(&function, span.start), span);
        }
        for measure in 0..self.elements.len() {
            if !(self.elements[measure].active && self.elements[measure].statement == MEASURE) {
                continue;
            }
            let span = self.elements[measure].span;
            let before = self.errors.len();
            let function = self.measure_function(measure);
            let read = self.errors.len() == before;
            self.errors.truncate(before);
            match function {
                Some(function) if read => variable(&self.elements[measure].name, function, span),
                _ => unread.push(span),
            }
        }
        if let Some(first) = variables.first() {
            self.notes.push((
                format!(
                    "the measures, as View has the solver compute them: {}",
                    written.join(", ")
                ),
                first.span,
            ));
        }
        if let Some(&first) = unread.first() {
            let count = unread.len();
            self.notes.push((
                format!(
                    "{count} measure{} mbexpr does not compute (a characteristic such as a part's kinetic energy or a point's total force ...) left out of the rows (here the first)",
                    if count == 1 { "" } else { "s" },
                ),
                first,
            ));
        }
        variables
    }

    /// The function of measure `measure`: a function measure's function, a
    /// kinematic measure's ([`Reader::kinematics`]); what it lacks is
    /// wrong. The measure is being read meanwhile (against loops).
    fn measure_function(&mut self, measure: usize) -> Option<Embedded> {
        let span = self.elements[measure].span;
        self.reading.push(measure);
        let function = if self.elements[measure].flags.is_empty() {
            self.elements[measure]
                .given
                .iter()
                .find(|(keyword, _, _)| keyword == "FUNCTION")
                .map(|&(_, command, position)| (command, position))
                .and_then(|(command, position)| self.function(command, position))
        } else {
            self.kinematics(measure)
                .map(|text| Embedded::pinned(&text, span.start))
        };
        self.reading.pop();
        function
    }

    /// The function of kinematic measure `measure`, which a function
    /// reads: of its `to_point` from its `from_point` (a `pt2pt`; ground's
    /// origin when none), of its `point` from ground's origin, or of the
    /// marker, part's centre of mass or element its `object` names
    /// ([`Reader::element_measure`]); components along
    /// `coordinate_rframe`'s axes (ground's when none), derivatives in
    /// `motion_rframe` (ground when none). What it cannot be is wrong at
    /// its place.
    fn kinematics(&mut self, measure: usize) -> Option<String> {
        let parameters = self.elements[measure].given.clone();
        let given = |keyword: &str| {
            parameters
                .iter()
                .find(|(name, _, _)| name == keyword)
                .map(|&(_, index, _)| index)
        };
        let kind = self.elements[measure].flags[0];
        let span = self.elements[measure].span;
        let component = given("COMPONENT").and_then(|index| self.word(index, "COMPONENT"));
        let frame = |reader: &mut Self, keyword: &str| match given(keyword) {
            Some(index) => reader.frame_marker(index, keyword),
            None => Some(0),
        };
        match kind {
            "ORIENT" => {
                let characteristic = given("CHARACTERISTIC")
                    .and_then(|index| self.word(index, "CHARACTERISTIC"))
                    .unwrap_or_else(|| "EULER_ANGLES".into());
                let (to, from) = (frame(self, "TO_FRAME")?, frame(self, "FROM_FRAME")?);
                let function = self.orientation(&characteristic, component.as_deref(), to, from);
                return self.read_measure(function, span);
            }
            "ANGLE" => {
                let mut ends = Vec::new();
                for keyword in ["FIRST_POINT", "MIDDLE_POINT", "LAST_POINT"] {
                    match given(keyword) {
                        Some(index) => ends.push(self.marker_id(index, keyword)?),
                        None => {
                            let lacks = "give its first_point, middle_point and last_point";
                            return self.read_measure(Err(lacks.into()), span);
                        }
                    }
                }
                let function = format!("INCANG({},{},{})", ends[0], ends[1], ends[2]);
                return Some(self.in_angle_unit(function));
            }
            _ => {}
        }
        let mut characteristic = given("CHARACTERISTIC")
            .and_then(|index| self.word(index, "CHARACTERISTIC"))
            .unwrap_or_else(|| "TRANSLATIONAL_DISPLACEMENT".into());
        let marker = |reader: &mut Self, keyword: &str| match given(keyword) {
            Some(index) => reader.marker_id(index, keyword).ok_or(()),
            None => Ok(0),
        };
        let axes = marker(self, "COORDINATE_RFRAME");
        let moving = marker(self, "MOTION_RFRAME");
        let (Ok(axes), Ok(moving)) = (axes, moving) else {
            return None;
        };
        // The measured marker and the one it is measured from, or why the
        // measure is not read (`None` where `marker_id` said so at its
        // place).
        let ends: Result<(u64, u64), Option<String>> = match kind {
            "PT2PT" => match (marker(self, "TO_POINT"), marker(self, "FROM_POINT")) {
                (Ok(to), Ok(from)) => Ok((to, from)),
                _ => Err(None),
            },
            "POINT" => marker(self, "POINT").map(|to| (to, 0)).map_err(|()| None),
            _ => {
                let name = given("OBJECT")
                    .and_then(|index| self.word(index, "OBJECT"))
                    .unwrap_or_default();
                match self.find(&name) {
                    Some(Entity::Marker(marker)) => {
                        self.markers[marker].id.map(|id| (id, 0)).ok_or(None)
                    }
                    Some(Entity::Part(part)) => match CENTRE_CHARACTERISTICS
                        .iter()
                        .find(|(centre, _)| *centre == characteristic)
                    {
                        Some(&(_, of_marker)) => {
                            characteristic = of_marker.into();
                            self.parts[part]
                                .centre_marker
                                .map(|id| (id, 0))
                                .ok_or_else(|| {
                                    Some(format!("{name} has no mass properties mbexpr reads"))
                                })
                        }
                        None => Err(Some(format!(
                            "a part's characteristic {} is not one mbexpr reads (cm_position, cm_velocity, cm_acceleration, cm_angular_velocity, cm_angular_acceleration)",
                            characteristic.to_ascii_lowercase()
                        ))),
                    },
                    Some(Entity::Element(element)) => {
                        let from_first = match given("FROM_FIRST") {
                            Some(index) => self.switch(index, "FROM_FIRST", span)?,
                            None => false,
                        };
                        let measured = ObjectMeasure {
                            element,
                            characteristic: &characteristic,
                            component: component.as_deref(),
                            from_first,
                            axes,
                            moving,
                        };
                        let function = self
                            .element_measure(&measured)
                            .map_err(|reason| format!("{name}: {reason}"));
                        return self.read_measure(function, span);
                    }
                    _ => Err(Some(format!(
                        "object = {name} names no marker, part or element the file creates"
                    ))),
                }
            }
        };
        let ends = match ends {
            Ok(ends) => ends,
            Err(Some(reason)) => return self.read_measure(Err(reason), span),
            Err(None) => return None,
        };
        let function =
            self.motion_function(&characteristic, component.as_deref(), ends, axes, moving);
        self.read_measure(function, span)
    }

    /// A measure's `function`, or what it lacks, wrong at the measure's
    /// place `span`.
    fn read_measure(&mut self, function: Result<String, String>, span: Span) -> Option<String> {
        function
            .map_err(|reason| {
                self.wrong(format!("a function reads this measure: {reason}"), span);
            })
            .ok()
    }

    /// The function of `characteristic` (a translational or angular
    /// displacement, velocity or acceleration) of marker `to` from marker
    /// `from` (`ends`), its `component` along the axes of marker `axes`,
    /// derivatives in the frame of marker `moving` (each 0 for ground's);
    /// angular quantities in the file's angle unit, as View has the solver
    /// compute its measures (`RTOD * AZ(21,22)` where angles are degrees).
    fn motion_function(
        &self,
        characteristic: &str,
        component: Option<&str>,
        (to, from): (u64, u64),
        axes: u64,
        moving: u64,
    ) -> Result<String, String> {
        let axis = axis_of(component)?.map(|axis| ["X", "Y", "Z"][axis]);
        if characteristic == "AX_AY_AZ_PROJECTION_ANGLES" {
            let Some(axis) = axis else {
                return Err("projection angles have no magnitude: give x_component, y_component or z_component".into());
            };
            return Ok(self.in_angle_unit(format!("A{axis}({to},{from})")));
        }
        let Some(&(_, along, magnitude, derivative)) = CHARACTERISTICS
            .iter()
            .find(|(name, _, _, _)| *name == characteristic)
        else {
            return Err(format!(
                "its characteristic {} is not one mbexpr reads (translational_displacement, translational_velocity, translational_acceleration, angular_velocity, angular_acceleration)",
                characteristic.to_ascii_lowercase()
            ));
        };
        let function = match (axis, derivative) {
            (Some(axis), true) => {
                format!("{}({to},{from},{axes},{moving})", along.replace("{}", axis))
            }
            (Some(axis), false) => format!("{}({to},{from},{axes})", along.replace("{}", axis)),
            (None, true) => format!("{magnitude}({to},{from},{moving})"),
            (None, false) => format!("{magnitude}({to},{from})"),
        };
        Ok(if along.starts_with('W') {
            self.in_angle_unit(function)
        } else {
            function
        })
    }

    /// `function`, an angle or an angular rate in radians, in the file's
    /// angle unit: View has the solver compute its measures in the units
    /// of the model (`RTOD * AZ(21,22)` where angles are degrees).
    fn in_angle_unit(&self, function: String) -> String {
        if self.degrees {
            format!("RTOD * {function}")
        } else {
            function
        }
    }

    /// The function of `component` of an orientation measure of
    /// `characteristic` (`measure create orient`): of marker `to`'s axes
    /// from marker `from`'s (0 for ground's) as Euler angles (body 3-1-3),
    /// yaw, pitch and roll, projection angles, the angles of any body or
    /// space sequence (`body_1_2_3`, `space_3_2_1`, Bryant angles: body
    /// 1-2-3), Euler parameters or direction cosines (`mat_i_j_component`:
    /// row i, column j). Angles are in the file's angle unit.
    fn orientation(
        &self,
        characteristic: &str,
        component: Option<&str>,
        to: u64,
        from: u64,
    ) -> Result<String, String> {
        let component = component.unwrap_or_default();
        let numbered = |prefix: &str| {
            component
                .strip_prefix(prefix)
                .and_then(|rest| rest.strip_suffix("_COMPONENT"))
                .and_then(|digit| digit.parse::<u8>().ok())
        };
        let angle = numbered("ANGLE_").filter(|k| (1..=3).contains(k));
        let wrong_component = |expected: &str| {
            format!(
                "its component {} is not one of a {} measure: give {expected}",
                component.to_ascii_lowercase(),
                characteristic.to_ascii_lowercase()
            )
        };
        let angles = "angle_1_component, angle_2_component or angle_3_component";
        let named = |names: [&str; 3]| match angle {
            Some(k) => {
                Ok(self.in_angle_unit(format!("{}({to},{from})", names[usize::from(k) - 1])))
            }
            None => Err(wrong_component(angles)),
        };
        match characteristic {
            "EULER_ANGLES" => named(["PSI", "THETA", "PHI"]),
            "YAW_PITCH_ROLL" => named(["YAW", "PITCH", "ROLL"]),
            "AX_AY_AZ_PROJECTION_ANGLES" => named(["AX", "AY", "AZ"]),
            "EULER_PARAMETERS" => match numbered("PARAM_").filter(|k| (1..=4).contains(k)) {
                Some(k) => Ok(format!("ORIENT(27,{k},{to},{from})")),
                None => Err(wrong_component("param_1_component ... param_4_component")),
            },
            "DIRECTION_COSINES" => {
                let entry = component
                    .strip_prefix("MAT_")
                    .and_then(|rest| rest.strip_suffix("_COMPONENT"))
                    .and_then(|rest| rest.split_once('_'))
                    .and_then(|(row, column)| {
                        Some((row.parse::<u8>().ok()?, column.parse::<u8>().ok()?))
                    })
                    .filter(|(row, column)| (1..=3).contains(row) && (1..=3).contains(column));
                match entry {
                    // ORIENT's direction cosines go by columns.
                    Some((row, column)) => {
                        Ok(format!("ORIENT(29,{},{to},{from})", row + 3 * (column - 1)))
                    }
                    None => Err(wrong_component("mat_1_1_component ... mat_3_3_component")),
                }
            }
            sequence => {
                let (body, axes) = match sequence {
                    "BRYANT_ANGLES" => (true, "1_2_3"),
                    _ => match (
                        sequence.strip_prefix("BODY_"),
                        sequence.strip_prefix("SPACE_"),
                    ) {
                        (Some(axes), _) => (true, axes),
                        (_, Some(axes)) => (false, axes),
                        _ => {
                            return Err(format!(
                                "its characteristic {} is not one mbexpr reads (euler_angles, yaw_pitch_roll, ax_ay_az_projection_angles, bryant_angles, body_1_2_3 ... space_3_2_3, euler_parameters, direction_cosines)",
                                characteristic.to_ascii_lowercase()
                            ));
                        }
                    },
                };
                let Some(system) = SEQUENCES.iter().position(|known| *known == axes) else {
                    return Err(format!(
                        "its characteristic {} is no sequence of turns mbexpr reads",
                        characteristic.to_ascii_lowercase()
                    ));
                };
                let system = system + if body { 1 } else { 13 };
                match angle {
                    Some(k) => Ok(self.in_angle_unit(format!("ORIENT({system},{k},{to},{from})"))),
                    None => Err(wrong_component(angles)),
                }
            }
        }
    }

    /// The function of an object measure of an element: a joint,
    /// primitive, motion or force, as View writes it. Its load
    /// (`element_force`, `element_torque`) is the element's function, on
    /// its I marker where `from_first` (`JOINT(11,0,1,0)`), on its J marker
    /// otherwise, along `coordinate_rframe`'s axes; its kinematics
    /// (displacements, velocities, accelerations, projection angles) are
    /// those of one of its markers from the other: of J from I where
    /// `from_first` (`AZ(2,1)` for a joint of I = 1, J = 2), of I from J
    /// otherwise. A motion on a joint is measured at the joint's markers.
    fn element_measure(&mut self, measured: &ObjectMeasure) -> Result<String, String> {
        let statement = self.elements[measured.element].statement;
        if let Some(offset) = LOADS
            .iter()
            .position(|load| *load == measured.characteristic)
        {
            let Some(&(_, function)) = LOAD_FUNCTIONS.iter().find(|(of, _)| *of == statement)
            else {
                return Err(format!(
                    "the {} of a {} is not one mbexpr computes",
                    measured.characteristic.to_ascii_lowercase(),
                    statement.to_ascii_lowercase()
                ));
            };
            // The components 1 to 4: the magnitude, then x, y and z.
            let along = axis_of(measured.component)?.map_or(1, |axis| axis + 2);
            let id = self.elements[measured.element].id.unwrap_or(0);
            let on_j = u8::from(!measured.from_first);
            return Ok(format!(
                "{function}({id},{on_j},{},{})",
                along + 4 * offset,
                measured.axes
            ));
        }
        let (i, j) = self.element_markers(measured.element)?;
        let ends = if measured.from_first { (j, i) } else { (i, j) };
        self.motion_function(
            measured.characteristic,
            measured.component,
            ends,
            measured.axes,
            measured.moving,
        )
    }

    /// The I and J markers of element `element` (a joint's, a primitive's,
    /// a force's; a motion on a joint, the joint's).
    fn element_markers(&mut self, element: usize) -> Result<(u64, u64), String> {
        let given = self.elements[element].given.clone();
        let mut ends = [None, None];
        for (keyword, index, _) in given {
            match keyword.as_str() {
                "I_MARKER_NAME" => ends[0] = self.marker_id(index, &keyword),
                "J_MARKER_NAME" => ends[1] = self.marker_id(index, &keyword),
                "JOINT_NAME" => {
                    let name = self.word(index, &keyword).unwrap_or_default();
                    if let Some(Entity::Element(joint)) = self.find(&name)
                        && self.elements[joint].statement == "JOINT"
                    {
                        return self.element_markers(joint);
                    }
                }
                _ => {}
            }
        }
        match ends {
            [Some(i), Some(j)] => Ok((i, j)),
            _ => Err(format!(
                "a {} has no I and J markers mbexpr measures from one another",
                self.elements[element].statement.to_ascii_lowercase()
            )),
        }
    }
}

/// The axis a measure's `component` is along (0, 1, 2 for x, y, z; `None`
/// for the magnitude), or what is wrong with it.
fn axis_of(component: Option<&str>) -> Result<Option<usize>, String> {
    match component {
        Some("X_COMPONENT") => Ok(Some(0)),
        Some("Y_COMPONENT") => Ok(Some(1)),
        Some("Z_COMPONENT") => Ok(Some(2)),
        Some("MAG_COMPONENT") => Ok(None),
        _ => Err(
            "give its component (x_component, y_component, z_component or mag_component)".into(),
        ),
    }
}

/// An object measure of an element, as [`Reader::element_measure`] reads
/// it.
struct ObjectMeasure<'c> {
    element: usize,
    /// View's characteristic, upper case.
    characteristic: &'c str,
    /// View's component, upper case.
    component: Option<&'c str>,
    /// Measured from (or at) the element's first marker, I.
    from_first: bool,
    /// The marker the components are along (0: ground).
    axes: u64,
    /// The marker the derivatives are taken in (0: ground).
    moving: u64,
}

/// The sequences of turns of the solver's ORIENT systems 1 to 12 (body
/// fixed; 13 to 24 the same about space-fixed axes), as View names them.
const SEQUENCES: [&str; 12] = [
    "1_2_3", "2_3_1", "3_1_2", "1_3_2", "2_1_3", "3_2_1", "1_2_1", "1_3_1", "2_1_2", "2_3_2",
    "3_1_3", "3_2_3",
];

/// The loads an element's object measure reads, in the order of the
/// components of the solver's element functions (1–4 the force, 5–8 the
/// torque).
const LOADS: [&str; 2] = ["ELEMENT_FORCE", "ELEMENT_TORQUE"];

/// The solver function of each element statement whose load a measure
/// reads.
const LOAD_FUNCTIONS: [(&str, &str); 12] = [
    ("JOINT", "JOINT"),
    ("JPRIM", "JPRIM"),
    ("MOTION", "MOTION"),
    ("SFORCE", "SFORCE"),
    ("VFORCE", "VFORCE"),
    ("VTORQUE", "VTORQ"),
    ("GFORCE", "GFORCE"),
    ("BUSHING", "BUSH"),
    ("BEAM", "BEAM"),
    ("SPRINGDAMPER", "SPDP"),
    ("CONTACT", "CONTACT"),
    ("FIELD", "FIELD"),
];

pub(super) fn new_statement(name: &str, id: Option<u64>, span: Span) -> Statement {
    Statement {
        name: name.into(),
        id,
        span,
        arguments: Vec::new(),
    }
}

pub(super) fn list_argument(
    statement: &mut Statement,
    keyword: &str,
    texts: Vec<String>,
    span: Span,
) {
    statement.arguments.push(Argument {
        keyword: keyword.into(),
        keyword_span: span,
        span,
        value: Value::List(
            texts
                .into_iter()
                .map(|text| ValueItem {
                    text: text.into(),
                    span,
                })
                .collect(),
        ),
    });
}

/// A `FUNCTION = function` argument at `span`.
pub(super) fn function_argument(statement: &mut Statement, function: Embedded, span: Span) {
    statement.arguments.push(Argument {
        keyword: "FUNCTION".into(),
        keyword_span: span,
        span,
        value: Value::Expression {
            text: function,
            span,
        },
    });
}

pub(super) fn numbers_argument(
    statement: &mut Statement,
    keyword: &str,
    values: &[f64],
    span: Span,
) {
    let texts = values.iter().map(|value| format!("{value:?}")).collect();
    list_argument(statement, keyword, texts, span);
}

pub(super) fn ids_argument(statement: &mut Statement, keyword: &str, id: u64, span: Span) {
    list_argument(statement, keyword, vec![id.to_string()], span);
}

pub(super) fn words_argument(statement: &mut Statement, keyword: &str, words: &[&str], span: Span) {
    let texts = words.iter().map(|word| word.to_string()).collect();
    list_argument(statement, keyword, texts, span);
}

pub(super) fn flag_argument(statement: &mut Statement, keyword: &str, span: Span) {
    statement.arguments.push(Argument {
        keyword: keyword.into(),
        keyword_span: span,
        span,
        value: Value::Flag,
    });
}

/// `origin`, a point on the z axis and one on the x axis of `frame`.
pub(super) fn place_arguments(
    statement: &mut Statement,
    keywords: [&str; 3],
    frame: &Frame,
    span: Span,
) {
    let origin = frame.origin;
    let points = [
        origin,
        origin + frame.axes.column(2),
        origin + frame.axes.column(0),
    ];
    for (keyword, point) in keywords.into_iter().zip(points) {
        numbers_argument(statement, keyword, &[point.x, point.y, point.z], span);
    }
}
