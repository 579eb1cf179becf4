//! Where the Jacobian of a model's equations can be nonzero, and how one
//! evaluation over dual numbers gives all of it.
//!
//! The states fall into groups: each DIFF (one state) and each body (its
//! 13). A DIFF's rate reads the groups its FUNCTION reads; a body's rates
//! read its own group and the groups every force element acting on it
//! reads (the bodies of the element's markers and what its expressions
//! read). That is the pattern, known when the model is compiled and the
//! same on every branch of every piecewise function (an IF's two branches
//! are both counted), so it is built once per model.
//!
//! Groups that no rate reads together share derivative directions (a
//! colouring of the groups, greedy, bodies and DIFFs apart): body colour
//! `c` seeds a body's 13 states in directions `13 c .. 13 c + 13`, DIFF
//! colour `c` one direction after the bodies'. Each rate then carries the
//! derivative of every state it reads in a direction of its own, and each
//! element and DIFF is differentiated only in the states it reads: a stack
//! or chain of bodies, whose rates read a body and its two neighbours, needs
//! three body colours (39 directions) whatever its length.
//!
//! A constrained model's multipliers (and its massless parts'
//! accelerations) are algebraic unknowns after the states (the bordered
//! pattern, [`Sparsity::new`]'s `holders`): a body's rates read the
//! multipliers of the equations moving it, and each equation's residual
//! what its bodies' rates read, so the pattern stays as sparse as the
//! joints. Without them (a model whose forces read the running solver's
//! values) bodies joined through any chain of joints read one another.
//!
//! A program that reads values of the running solver (a force reading a
//! joint's reaction) has a dense pattern: those values are settled with
//! the motion of every body.

use super::forces::body_of;
use super::{BODY_STATES, KINEMATIC_RATES, Source, body_offset};
use crate::compile::Program;
use crate::integrate::linalg::Pattern;
use crate::scene::Target;
use crate::simulate::constraints::{Holder, holders};
use crate::simulate::model::{Force, Model};

/// The pattern of a model's Jacobian and the seeding that fills it.
pub(crate) struct Sparsity {
    pub(crate) pattern: Pattern,
    /// The derivative direction each state is seeded in.
    pub(crate) direction: Vec<usize>,
    /// How many directions there are.
    pub(crate) directions: usize,
    /// For each row, from `row_starts[row]` to `row_starts[row + 1]`: the
    /// position of each of its entries among the pattern's, and the
    /// direction its derivative is read from.
    row_starts: Vec<usize>,
    entries: Vec<(usize, usize)>,
}

impl Sparsity {
    /// The sparsity of `model`'s equations, whose expression `e` is output
    /// `output_of[e]` of `program`, the program's inputs coming from
    /// `sources`. With `holders` (the joints' held equations by holder),
    /// the multipliers are algebraic unknowns after the states (the
    /// index-1 form's Jacobian in `(y, λ)`, see [`crate::integrate::linalg`]):
    /// a body's rates read the multipliers of the equations that move it,
    /// and each equation's residual the states and multipliers its
    /// bodies' rates read. Without, the multipliers are eliminated and
    /// bodies joined through any chain of joints read what any of them
    /// reads.
    pub(crate) fn new(
        model: &Model,
        program: &Program,
        (sources, output_of): (&[Source], &[Option<usize>]),
        holders: Option<&[Holder]>,
    ) -> Sparsity {
        let bodies = model.scene.bodies.len();
        let diffs = model.diffs.len();
        let n = diffs + BODY_STATES * bodies;
        let held = holders.unwrap_or_default();
        let mut first_equation = Vec::with_capacity(held.len());
        let mut equations = 0;
        for holder in held {
            first_equation.push(equations);
            equations += holder.equations;
        }
        let groups = bodies + diffs + held.len();
        let kind_of = |group: usize| {
            if group < bodies {
                Kind::Body
            } else if group < bodies + diffs {
                Kind::Diff
            } else {
                Kind::Equations
            }
        };
        let states_of = |group: usize| match kind_of(group) {
            Kind::Body => {
                let offset = body_offset(model, group);
                offset..offset + BODY_STATES
            }
            Kind::Diff => {
                let diff = group - bodies;
                diff..diff + 1
            }
            Kind::Equations => {
                let holder = group - bodies - diffs;
                let first = n + first_equation[holder];
                first..first + held[holder].equations
            }
        };
        // The groups each output reads.
        let output_groups: Vec<Vec<usize>> = program
            .inputs_of_outputs()
            .iter()
            .map(|inputs| {
                let mut read: Vec<usize> = inputs
                    .iter()
                    .filter_map(|&input| match sources[input] {
                        Source::Body(body, _) => Some(body),
                        Source::State(diff) => Some(bodies + diff),
                        Source::Time
                        | Source::Constant(_)
                        | Source::Solver(_)
                        | Source::Sensor(_) => None,
                    })
                    .collect();
                read.sort_unstable();
                read.dedup();
                read
            })
            .collect();
        let expression_groups = |expression: Option<usize>| {
            expression
                .and_then(|expression| output_of[expression])
                .map_or(&[][..], |output| output_groups[output].as_slice())
        };
        // The groups each group's rates read.
        let mut reads: Vec<Vec<usize>> = (0..groups).map(|group| vec![group]).collect();
        for (diff, statement) in model.diffs.iter().enumerate() {
            reads[bodies + diff].extend(expression_groups(Some(statement.function)));
        }
        let body_of = |target: &Target| body_of(model, target);
        for force in &model.forces {
            let (touched, expressions): (Vec<usize>, Vec<Option<usize>>) = match force {
                Force::Translational {
                    i, j, magnitude, ..
                }
                | Force::Rotational {
                    i, j, magnitude, ..
                } => (
                    [body_of(i), body_of(j)].into_iter().flatten().collect(),
                    vec![Some(*magnitude)],
                ),
                Force::Vector {
                    i,
                    reaction,
                    axes,
                    force,
                    torque,
                } => (
                    [body_of(i), body_of(axes), *reaction]
                        .into_iter()
                        .flatten()
                        .collect(),
                    force.iter().chain(torque).copied().collect(),
                ),
                Force::Contact(contact) => (
                    [body_of(&contact.i.marker), body_of(&contact.j.marker)]
                        .into_iter()
                        .flatten()
                        .collect(),
                    Vec::new(),
                ),
            };
            let mut read = touched.clone();
            for &expression in &expressions {
                read.extend(expression_groups(expression));
            }
            for &body in &touched {
                reads[body].extend(&read);
            }
        }
        if holders.is_some() {
            // A body's rates read the multipliers of the equations moving
            // it and the states of the bodies those equations move (the
            // rows of `G` the multipliers load it through); an equation's
            // residual reads its bodies' rates.
            for (holder, group) in held.iter().zip(bodies + diffs..) {
                for &body in &holder.bodies {
                    reads[body].push(group);
                    reads[body].extend(&holder.bodies);
                }
            }
            for (holder, group) in held.iter().zip(bodies + diffs..) {
                let read: Vec<usize> = holder
                    .bodies
                    .iter()
                    .flat_map(|&body| reads[body].clone())
                    .collect();
                reads[group].extend(read);
            }
        } else {
            // Bodies joined (through any chain of joints) share their
            // multipliers: each one's rates read what any of them reads.
            for component in joined(model) {
                let mut read: Vec<usize> = component
                    .iter()
                    .flat_map(|&body| reads[body].clone())
                    .collect();
                read.sort_unstable();
                read.dedup();
                for &body in &component {
                    reads[body].clone_from(&read);
                }
            }
        }
        // The values of the running solver a force reads (a joint's
        // reaction ...) are settled with every body's motion: every rate
        // may read every state.
        if sources
            .iter()
            .any(|source| matches!(source, Source::Solver(_)))
        {
            for read in &mut reads {
                *read = (0..groups).collect();
            }
        }
        for read in &mut reads {
            read.sort_unstable();
            read.dedup();
        }
        let colour = colouring(&reads, kind_of);
        let colours_of = |kind: Kind| {
            (0..groups)
                .filter(|&group| kind_of(group) == kind)
                .map(|group| colour[group] + 1)
                .max()
                .unwrap_or(0)
        };
        let body_colours = colours_of(Kind::Body);
        let diff_colours = colours_of(Kind::Diff);
        let width = held
            .iter()
            .map(|holder| holder.equations)
            .max()
            .unwrap_or(0);
        let dimension = n + equations;
        let mut direction = vec![0; dimension];
        for (group, &group_colour) in colour.iter().enumerate() {
            for (index, state) in states_of(group).enumerate() {
                direction[state] = match kind_of(group) {
                    Kind::Body => BODY_STATES * group_colour + index,
                    Kind::Diff => BODY_STATES * body_colours + group_colour,
                    Kind::Equations => {
                        BODY_STATES * body_colours + diff_colours + width * group_colour + index
                    }
                };
            }
        }
        let directions =
            BODY_STATES * body_colours + diff_colours + width * colours_of(Kind::Equations);
        // A body's position and orientation rates (its first seven) are
        // its own velocity and spin: they read its own states only, and
        // the LU meets no neighbour's block in those rows.
        let entries_of = |group: usize| {
            let columns: Vec<usize> = reads[group].iter().flat_map(|&g| states_of(g)).collect();
            let own: Vec<usize> = states_of(group).collect();
            let body = kind_of(group) == Kind::Body;
            states_of(group).enumerate().flat_map(move |(index, row)| {
                let read = if body && index < KINEMATIC_RATES {
                    own.clone()
                } else {
                    columns.clone()
                };
                read.into_iter().map(move |column| (row, column))
            })
        };
        // Those rows are eliminated ahead of the sparse LU, which then
        // factorises six unknowns a body.
        let kinematic = (0..bodies).map(|body| {
            let offset = body_offset(model, body);
            offset..offset + KINEMATIC_RATES
        });
        let pattern = Pattern::new(dimension, (0..groups).flat_map(entries_of))
            .with_eliminated(kinematic.collect());
        let mut row_entries: Vec<Vec<(usize, usize)>> = vec![Vec::new(); dimension];
        for (position, (row, column)) in pattern.entries().enumerate() {
            row_entries[row].push((position, direction[column]));
        }
        let mut row_starts = Vec::with_capacity(dimension + 1);
        row_starts.push(0);
        let mut entries = Vec::with_capacity(pattern.len());
        for row in row_entries {
            entries.extend(row);
            row_starts.push(entries.len());
        }
        Sparsity {
            pattern,
            direction,
            directions,
            row_starts,
            entries,
        }
    }

    /// The entries of row `row`: each one's position among the pattern's
    /// entries and the direction its derivative is read from.
    pub(crate) fn row(&self, row: usize) -> &[(usize, usize)] {
        &self.entries[self.row_starts[row]..self.row_starts[row + 1]]
    }
}

/// What a group of states is: a body's 13, a DIFF's one, or a holder's
/// multipliers (algebraic unknowns).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Body,
    Diff,
    Equations,
}

/// A colour for each group such that no two groups read by one group's
/// rates share one; each kind of group is coloured apart (its own
/// directions). Greedy, in group order: the smallest colour free.
fn colouring(reads: &[Vec<usize>], kind_of: impl Fn(usize) -> Kind) -> Vec<usize> {
    let groups = reads.len();
    let mut readers: Vec<Vec<usize>> = vec![Vec::new(); groups];
    for (row, read) in reads.iter().enumerate() {
        for &group in read {
            readers[group].push(row);
        }
    }
    let mut colour = vec![usize::MAX; groups];
    let mut taken = Vec::new();
    for group in 0..groups {
        taken.clear();
        for &row in &readers[group] {
            for &other in &reads[row] {
                if kind_of(other) == kind_of(group) && colour[other] != usize::MAX {
                    taken.push(colour[other]);
                }
            }
        }
        taken.sort_unstable();
        taken.dedup();
        colour[group] = (0..)
            .find(|candidate| taken.binary_search(candidate).is_err())
            .expect("a free colour");
    }
    colour
}

/// The sets of two or more bodies that joints join, directly or through
/// other bodies (ground joins nothing: a body held to ground moves on its
/// own).
fn joined(model: &Model) -> Vec<Vec<usize>> {
    let links = holders(model).into_iter().flat_map(|holder| {
        holder
            .bodies
            .windows(2)
            .map(|pair| (pair[0], pair[1]))
            .collect::<Vec<_>>()
    });
    crate::simulate::model::linked_groups(model.scene.bodies.len(), links)
}
