//! Small blocks of states eliminated ahead of the sparse LU.
//!
//! A rigid body's position and orientation rates are its own velocity and
//! spin: their rows of `J` read only the body's own states. Ordered first,
//! the iteration matrix `σ I − J` is
//!
//! ```text
//! [ E   −B ]     E = σ I − J_kk, block diagonal (one small block a body)
//! [ −C   S₀ ]    S₀ = σ I − J_rr (velocities, DIFFs, multipliers)
//! ```
//!
//! and the kept unknowns solve the Schur complement `S = S₀ − C E⁻¹ B`,
//! which has the pattern of `S₀` (a row that reads a body's position reads
//! its velocity too): the sparse LU then factorises 6 unknowns a body, not
//! 13, and its cost falls with the cube of the block. Each block of `E` is
//! inverted densely (it is regular for every shift of a Radau step: its
//! spin part is skew), and a solve is
//!
//! ```text
//! y = E⁻¹ r_k,   S x_r = r_r + C y,   x_k = y + E⁻¹ B x_r.
//! ```

use std::ops::Range;

use nalgebra::ComplexField;

use super::Pattern;

/// One eliminated block: where its entries are, and which kept unknowns it
/// reads and is read by.
struct Block {
    /// Its unknowns, in the full numbering.
    unknowns: Range<usize>,
    /// The entries of `J_kk` in the block: (row, column) within it and the
    /// entry's position among the pattern's.
    own: Vec<(usize, usize, usize)>,
    /// The kept unknowns (reduced numbering) the block's rows read.
    reads: Vec<usize>,
    /// The entries of `B`: row within the block, index into `reads`,
    /// position among the pattern's.
    read_entries: Vec<(usize, usize, usize)>,
    /// The kept unknowns (reduced numbering) whose rows read the block.
    readers: Vec<usize>,
    /// The entries of `C`: index into `readers`, column within the block,
    /// position among the pattern's.
    reader_entries: Vec<(usize, usize, usize)>,
    /// The position in the reduced pattern of entry `(readers[r],
    /// reads[c])`, at `r * reads.len() + c`.
    fill: Vec<usize>,
}

impl Block {
    /// The entries of the reduced pattern `C E⁻¹ B` fills: each reader's
    /// row in each read column, in the order of [`Block::fill`].
    fn fill_entries(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.readers
            .iter()
            .flat_map(|&row| self.reads.iter().map(move |&column| (row, column)))
    }
}

/// How a pattern's unknowns split into eliminated blocks and kept ones,
/// and the pattern of the kept ones' Schur complement.
pub(super) struct Elimination {
    blocks: Vec<Block>,
    /// The reduced index of each unknown, `None` for an eliminated one.
    reduced: Vec<Option<usize>>,
    /// The kept unknowns' pattern (with the blocks' fill).
    pub(super) pattern: Pattern,
    /// Entries between kept unknowns: (position in the full pattern,
    /// position in the reduced one).
    kept_entries: Vec<(usize, usize)>,
    /// The reduced pattern's diagonal positions of the kept states (the
    /// entries the shift is added to).
    shifted: Vec<usize>,
}

/// The numbers of one factorisation's blocks, each block's in one run of
/// a flat store (row-major): its inverse `E⁻¹`, its `C` and its `E⁻¹ B`.
pub(super) struct BlockNumbers<T> {
    inverse: Vec<T>,
    read_by: Vec<T>,
    reach: Vec<T>,
    /// A block's matrix being inverted, and a block's part of a solve.
    work: Vec<T>,
    part: Vec<T>,
    /// The nonzero entries of a block's `E⁻¹ B`: row, column, position.
    reach_entries: Vec<(usize, usize, usize)>,
}

impl<T> Default for BlockNumbers<T> {
    fn default() -> Self {
        BlockNumbers {
            inverse: Vec::new(),
            read_by: Vec::new(),
            reach: Vec::new(),
            work: Vec::new(),
            part: Vec::new(),
            reach_entries: Vec::new(),
        }
    }
}

impl Elimination {
    /// The split of `pattern`, whose first `states` unknowns are states,
    /// with `blocks` eliminated; no block is eliminated when they are not
    /// disjoint ranges of states in increasing order with no entry between
    /// two of them (then `J_kk` would not be block diagonal), or when their
    /// fill would make the kept unknowns' pattern larger than `pattern`.
    pub(super) fn new(pattern: &Pattern, states: usize, blocks: &[Range<usize>]) -> Elimination {
        let n = pattern.dimension();
        let ordered = blocks.windows(2).all(|pair| pair[0].end <= pair[1].start)
            && blocks
                .iter()
                .all(|block| block.start < block.end && block.end <= states);
        let mut block_of = vec![None; n];
        if ordered {
            for (index, block) in blocks.iter().enumerate() {
                for unknown in block.clone() {
                    block_of[unknown] = Some(index);
                }
            }
        }
        let apart =
            pattern
                .entries()
                .all(|(row, column)| match (block_of[row], block_of[column]) {
                    (Some(a), Some(b)) => a == b,
                    _ => true,
                });
        let blocks: &[Range<usize>] = if ordered && apart { blocks } else { &[] };
        if blocks.is_empty() {
            block_of.fill(None);
        }
        let mut reduced = vec![None; n];
        let mut kept = 0;
        for (unknown, slot) in reduced.iter_mut().enumerate() {
            if block_of[unknown].is_none() {
                *slot = Some(kept);
                kept += 1;
            }
        }
        let mut eliminated: Vec<Block> = blocks
            .iter()
            .map(|unknowns| Block {
                unknowns: unknowns.clone(),
                own: Vec::new(),
                reads: Vec::new(),
                read_entries: Vec::new(),
                readers: Vec::new(),
                reader_entries: Vec::new(),
                fill: Vec::new(),
            })
            .collect();
        let mut kept_pairs = Vec::new();
        for (position, (row, column)) in pattern.entries().enumerate() {
            match (block_of[row], block_of[column]) {
                (Some(block), Some(_)) => {
                    let start = eliminated[block].unknowns.start;
                    eliminated[block]
                        .own
                        .push((row - start, column - start, position));
                }
                (Some(block), None) => {
                    let start = eliminated[block].unknowns.start;
                    let column = reduced[column].expect("a kept unknown");
                    eliminated[block]
                        .read_entries
                        .push((row - start, column, position));
                }
                (None, Some(block)) => {
                    let start = eliminated[block].unknowns.start;
                    let row = reduced[row].expect("a kept unknown");
                    eliminated[block]
                        .reader_entries
                        .push((row, column - start, position));
                }
                (None, None) => {
                    kept_pairs.push((
                        position,
                        reduced[row].expect("kept"),
                        reduced[column].expect("kept"),
                    ));
                }
            }
        }
        for block in &mut eliminated {
            block.reads = distinct(block.read_entries.iter().map(|entry| entry.1));
            block.readers = distinct(block.reader_entries.iter().map(|entry| entry.0));
            for entry in &mut block.read_entries {
                entry.1 = block.reads.binary_search(&entry.1).expect("read");
            }
            for entry in &mut block.reader_entries {
                entry.0 = block.readers.binary_search(&entry.0).expect("reader");
            }
        }
        let reduced_pattern = Pattern::new(
            kept,
            kept_pairs
                .iter()
                .map(|&(_, row, column)| (row, column))
                .chain(eliminated.iter().flat_map(Block::fill_entries)),
        );
        // Elimination that fills the kept unknowns' pattern beyond the full
        // one's would cost more than it saves.
        if reduced_pattern.len() > pattern.len() {
            return Elimination::new(pattern, states, &[]);
        }
        let position = |row: usize, column: usize| {
            reduced_pattern
                .position(row, column)
                .expect("an entry of the reduced pattern")
        };
        for block in &mut eliminated {
            block.fill = block
                .fill_entries()
                .map(|(row, column)| position(row, column))
                .collect();
        }
        let kept_entries = kept_pairs
            .iter()
            .map(|&(full, row, column)| (full, position(row, column)))
            .collect();
        let shifted = (0..states)
            .filter_map(|state| reduced[state])
            .map(|kept| reduced_pattern.diagonal[kept])
            .collect();
        Elimination {
            blocks: eliminated,
            reduced,
            pattern: reduced_pattern,
            kept_entries,
            shifted,
        }
    }

    /// The dimension of the full system.
    pub(super) fn dimension(&self) -> usize {
        self.reduced.len()
    }

    /// Eliminates the blocks of `shift I − J` (`J` the full pattern's
    /// `values`): the Schur complement's values into `reduced_values` (on
    /// the reduced pattern) and the blocks' numbers into `numbers`. False
    /// when a block is singular.
    pub(super) fn eliminate<T: Scalar>(
        &self,
        values: &[f64],
        shift: T,
        reduced_values: &mut [T],
        numbers: &mut BlockNumbers<T>,
    ) -> bool {
        let zero = T::from(0.0);
        let value = |position: usize| T::from(values[position]);
        reduced_values.fill(zero);
        for &(full, kept) in &self.kept_entries {
            reduced_values[kept] = -value(full);
        }
        for &at in &self.shifted {
            reduced_values[at] += shift;
        }
        let BlockNumbers {
            inverse,
            read_by,
            reach,
            work,
            reach_entries,
            ..
        } = numbers;
        inverse.clear();
        read_by.clear();
        reach.clear();
        for block in &self.blocks {
            let size = block.unknowns.len();
            let (reads, readers) = (block.reads.len(), block.readers.len());
            work.clear();
            work.resize(size * size, zero);
            for diagonal in 0..size {
                work[diagonal * size + diagonal] = shift;
            }
            for &(row, column, position) in &block.own {
                work[row * size + column] -= value(position);
            }
            let at = inverse.len();
            inverse.resize(at + size * size, zero);
            if !invert(work, size, &mut inverse[at..]) {
                return false;
            }
            let block_inverse = &inverse[at..];
            // E⁻¹ B, from B's entries.
            let at = reach.len();
            reach.resize(at + size * reads, zero);
            let block_reach = &mut reach[at..];
            for &(row, column, position) in &block.read_entries {
                let entry = value(position);
                if entry == zero {
                    continue;
                }
                for k in 0..size {
                    block_reach[k * reads + column] += block_inverse[k * size + row] * entry;
                }
            }
            let at = read_by.len();
            read_by.resize(at + readers * size, zero);
            let block_read_by = &mut read_by[at..];
            for &(row, column, position) in &block.reader_entries {
                block_read_by[row * size + column] = value(position);
            }
            // C E⁻¹ B over the nonzero entries of E⁻¹ B (a body's position
            // rows read only its velocity, its orientation rows its spin).
            reach_entries.clear();
            reach_entries.extend(
                (0..size * reads)
                    .filter(|&at| block_reach[at] != zero)
                    .map(|at| (at / reads, at % reads, at)),
            );
            for row in 0..readers {
                let coupling = &block_read_by[row * size..(row + 1) * size];
                let fill = &block.fill[row * reads..(row + 1) * reads];
                for &(k, column, at) in reach_entries.iter() {
                    reduced_values[fill[column]] -= coupling[k] * block_reach[at];
                }
            }
        }
        true
    }

    /// The reduced right-hand side `r_r + C E⁻¹ r_k` of `full` (every
    /// unknown's) into `reduced`, keeping each block's `E⁻¹ r_k` in place
    /// of its `r_k` in `full`.
    pub(super) fn forward<T: Scalar>(
        &self,
        numbers: &mut BlockNumbers<T>,
        full: &mut [T],
        reduced: &mut [T],
    ) {
        for (unknown, slot) in self.reduced.iter().enumerate() {
            if let Some(kept) = slot {
                reduced[*kept] = full[unknown];
            }
        }
        let (mut inverse_at, mut read_by_at) = (0, 0);
        for block in &self.blocks {
            let size = block.unknowns.len();
            let inverse = &numbers.inverse[inverse_at..inverse_at + size * size];
            let read_by = &numbers.read_by[read_by_at..read_by_at + block.readers.len() * size];
            inverse_at += size * size;
            read_by_at += read_by.len();
            let part = &mut numbers.part;
            part.clear();
            part.extend_from_slice(&full[block.unknowns.clone()]);
            for (row, slot) in full[block.unknowns.clone()].iter_mut().enumerate() {
                *slot = dot(&inverse[row * size..(row + 1) * size], part);
            }
            let solved = &full[block.unknowns.clone()];
            for (index, &row) in block.readers.iter().enumerate() {
                reduced[row] += dot(&read_by[index * size..(index + 1) * size], solved);
            }
        }
    }

    /// The full solution from the kept unknowns' (`reduced`, solved) and
    /// the blocks' `E⁻¹ r_k` (in `full`, from [`Elimination::forward`]).
    pub(super) fn back<T: Scalar>(&self, numbers: &BlockNumbers<T>, full: &mut [T], reduced: &[T]) {
        let mut reach_at = 0;
        for block in &self.blocks {
            let (size, reads) = (block.unknowns.len(), block.reads.len());
            let reach = &numbers.reach[reach_at..reach_at + size * reads];
            reach_at += reach.len();
            for (row, slot) in full[block.unknowns.clone()].iter_mut().enumerate() {
                for (&entry, &column) in reach[row * reads..(row + 1) * reads]
                    .iter()
                    .zip(&block.reads)
                {
                    *slot += entry * reduced[column];
                }
            }
        }
        for (unknown, slot) in self.reduced.iter().enumerate() {
            if let Some(kept) = slot {
                full[unknown] = reduced[*kept];
            }
        }
    }
}

/// The numbers the elimination works in: `f64` and complex.
pub(super) trait Scalar: ComplexField + Copy + From<f64> {}

impl<T: ComplexField + Copy + From<f64>> Scalar for T {}

/// `Σ a_k b_k`.
fn dot<T: Scalar>(a: &[T], b: &[T]) -> T {
    a.iter()
        .zip(b)
        .fold(T::from(0.0), |sum, (&a, &b)| sum + a * b)
}

/// The inverse of the `size × size` row-major `matrix` (destroyed) into
/// `inverse`, by Gauss-Jordan elimination with partial pivoting; false when
/// a pivot is zero or not finite.
fn invert<T: Scalar>(matrix: &mut [T], size: usize, inverse: &mut [T]) -> bool {
    inverse.fill(T::from(0.0));
    for diagonal in 0..size {
        inverse[diagonal * size + diagonal] = T::from(1.0);
    }
    for column in 0..size {
        let pivot_row = (column..size)
            .max_by(|&a, &b| {
                matrix[a * size + column]
                    .norm1()
                    .partial_cmp(&matrix[b * size + column].norm1())
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .expect("a row");
        let pivot = matrix[pivot_row * size + column];
        if pivot == T::from(0.0) || !pivot.is_finite() {
            return false;
        }
        if pivot_row != column {
            for k in 0..size {
                matrix.swap(pivot_row * size + k, column * size + k);
                inverse.swap(pivot_row * size + k, column * size + k);
            }
        }
        let scale = T::from(1.0) / pivot;
        for k in 0..size {
            matrix[column * size + k] *= scale;
            inverse[column * size + k] *= scale;
        }
        for row in (0..size).filter(|&row| row != column) {
            let factor = matrix[row * size + column];
            if factor == T::from(0.0) {
                continue;
            }
            for k in 0..size {
                let (pivot_entry, inverse_entry) =
                    (matrix[column * size + k], inverse[column * size + k]);
                matrix[row * size + k] -= factor * pivot_entry;
                inverse[row * size + k] -= factor * inverse_entry;
            }
        }
    }
    true
}

/// The distinct values of `values`, increasing.
fn distinct(values: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut values: Vec<usize> = values.collect();
    values.sort_unstable();
    values.dedup();
    values
}
