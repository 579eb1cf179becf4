//! The VARIABLEs of a model as a graph, each reading the ones its function
//! names in `VARVAL`: the loops among them, each reported once, and the
//! order that evaluates each one once, after the ones it reads. Strongly
//! connected components without recursion, so a chain of any length costs
//! its length.

use std::collections::HashMap;

use petgraph::algo::kosaraju_scc;
use petgraph::graph::{DiGraph, NodeIndex};

use crate::catalog::Function;
use crate::check::{Argument, Checked, NodeKind, Reference, visit};
use crate::span::Span;

/// Which VARIABLE reads which, with where (an edge from reader to read).
#[derive(Default)]
pub(crate) struct Reads {
    graph: DiGraph<u64, Read>,
    nodes: HashMap<u64, NodeIndex>,
}

/// One `VARVAL(id)`: where it stands, and the expression it is in.
#[derive(Clone, Copy)]
struct Read {
    span: Span,
    expression: usize,
}

/// A loop among VARIABLEs, reported at the reference that closes it.
pub(crate) struct Loop {
    /// The loop's smallest id, where the cycle starts.
    pub(crate) first: u64,
    /// `VARIABLE/3 -> VARIABLE/5 -> VARIABLE/3`.
    pub(crate) cycle: String,
    /// The `VARVAL` that leads back to the first.
    pub(crate) span: Span,
    /// The expression that `VARVAL` is in.
    pub(crate) expression: usize,
}

impl Reads {
    fn node(&mut self, id: u64) -> NodeIndex {
        *self
            .nodes
            .entry(id)
            .or_insert_with(|| self.graph.add_node(id))
    }

    /// VARIABLE `reader` reads VARIABLE `read` at `span` of expression `expression`.
    pub(crate) fn add(&mut self, reader: u64, read: u64, span: Span, expression: usize) {
        let (from, to) = (self.node(reader), self.node(read));
        self.graph.add_edge(from, to, Read { span, expression });
    }

    /// Every loop, once: for each group of VARIABLEs that read each other,
    /// the shortest cycle from its smallest id back to it.
    pub(crate) fn loops(&self) -> Vec<Loop> {
        let mut loops = Vec::new();
        for component in kosaraju_scc(&self.graph) {
            let looped =
                component.len() > 1 || self.graph.find_edge(component[0], component[0]).is_some();
            if !looped {
                continue;
            }
            let start = *component
                .iter()
                .min_by_key(|&&node| self.graph[node])
                .expect("a component has a node");
            loops.push(self.cycle_from(start, &component));
        }
        loops.sort_by_key(|found| found.first);
        loops
    }

    /// The shortest path from `start` back to itself inside `component`
    /// (breadth first).
    fn cycle_from(&self, start: NodeIndex, component: &[NodeIndex]) -> Loop {
        let inside: std::collections::HashSet<NodeIndex> = component.iter().copied().collect();
        let mut came_from: HashMap<NodeIndex, (NodeIndex, Read)> = HashMap::new();
        let mut queue = std::collections::VecDeque::from([start]);
        let mut closing = None;
        'search: while let Some(node) = queue.pop_front() {
            for edge in self.graph.edges(node) {
                use petgraph::visit::EdgeRef;
                let target = edge.target();
                if target == start {
                    closing = Some((node, *edge.weight()));
                    break 'search;
                }
                if inside.contains(&target) && !came_from.contains_key(&target) {
                    came_from.insert(target, (node, *edge.weight()));
                    queue.push_back(target);
                }
            }
        }
        let (last, read) = closing.expect("a component with a loop leads back to its start");
        // Back from the node that closes the loop to the start, then turned round.
        let mut between = Vec::new();
        let mut node = last;
        while node != start {
            between.push(self.graph[node]);
            node = came_from[&node].0;
        }
        let mut path = vec![self.graph[start]];
        path.extend(between.into_iter().rev());
        path.push(self.graph[start]);
        let cycle: Vec<String> = path.iter().map(|id| format!("VARIABLE/{id}")).collect();
        Loop {
            first: self.graph[start],
            cycle: cycle.join(" -> "),
            span: read.span,
            expression: read.expression,
        }
    }
}

/// The VARIABLEs of `variables` in an order that evaluates each one after
/// the ones it reads, and the ones in loops (which have no value).
pub fn evaluation_order(variables: &HashMap<u64, Checked>) -> (Vec<u64>, Vec<u64>) {
    let mut reads = Reads::default();
    let mut ids: Vec<u64> = variables.keys().copied().collect();
    ids.sort_unstable();
    for &id in &ids {
        reads.node(id);
        visit(&variables[&id].root, &mut |node| {
            if let NodeKind::Call(Function::Varval, args) = &node.kind
                && let Some(Argument::Object(Reference::Id(read), _)) = args.first()
                && variables.contains_key(read)
            {
                reads.add(id, *read, node.span, 0);
            }
        });
    }
    let (mut order, mut looped) = (Vec::new(), Vec::new());
    // Kosaraju gives the components in postorder: a VARIABLE's reads first.
    for component in kosaraju_scc(&reads.graph) {
        let single =
            component.len() == 1 && reads.graph.find_edge(component[0], component[0]).is_none();
        let target = if single { &mut order } else { &mut looped };
        target.extend(component.iter().map(|&node| reads.graph[node]));
    }
    looped.sort_unstable();
    (order, looped)
}
