//! Expression text joined from pieces of a file, with the way back: every
//! byte of the joined text maps to its byte in the file.

use crate::span::Span;

/// An expression as the language sees it (continuations removed) and where
/// each piece of it stands in the file.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Embedded {
    /// The joined expression text.
    pub text: String,
    /// `(offset in text, offset in file)` at the start of each piece, in order.
    pieces: Vec<(usize, usize)>,
}

impl Embedded {
    /// Appends `piece`, which starts at byte `file_offset` of the file.
    pub fn push(&mut self, piece: &str, file_offset: usize) {
        if piece.is_empty() {
            return;
        }
        self.pieces.push((self.text.len(), file_offset));
        self.text.push_str(piece);
    }

    /// A text mbexpr writes for a statement (a BUSHING's force component),
    /// every byte of which stands for the statement at `file_offset`.
    pub fn pinned(text: &str, file_offset: usize) -> Embedded {
        let mut embedded = Embedded::default();
        let mut buffer = [0; 4];
        for character in text.chars() {
            embedded.push(character.encode_utf8(&mut buffer), file_offset);
        }
        embedded
    }

    /// An empty expression written at byte `file_offset` of the file (a
    /// View command's `function = ""`), so that a message about it points
    /// there.
    pub fn empty_at(file_offset: usize) -> Embedded {
        Embedded {
            text: String::new(),
            pieces: vec![(0, file_offset)],
        }
    }

    /// This text with each `(span, replacement)` (spans in the joined
    /// text, in order, not overlapping) put in place of what it covers; a
    /// replacement maps to the file where the text it replaces starts, the
    /// rest of the text where it did.
    pub fn replaced(&self, replacements: &[(Span, String)]) -> Embedded {
        let mut result = Embedded::default();
        let mut copied = 0;
        for (span, replacement) in replacements {
            self.copy_into(&mut result, copied, span.start);
            result.push(replacement, self.file_offset(span.start));
            copied = span.end;
        }
        self.copy_into(&mut result, copied, self.text.len());
        if result.pieces.is_empty() {
            result.pieces.push((0, self.file_offset(0)));
        }
        result
    }

    /// Appends bytes `start..end` of this text to `result`, piece by piece.
    fn copy_into(&self, result: &mut Embedded, start: usize, end: usize) {
        let mut at = start;
        while at < end {
            let next_piece = self
                .pieces
                .iter()
                .map(|&(piece_start, _)| piece_start)
                .find(|&piece_start| piece_start > at)
                .unwrap_or(self.text.len())
                .min(end);
            result.push(&self.text[at..next_piece], self.file_offset(at));
            at = next_piece;
        }
    }

    /// The file offset of byte `offset` of the joined text (the end of the
    /// text maps to just after its last byte).
    pub fn file_offset(&self, offset: usize) -> usize {
        let index = self
            .pieces
            .partition_point(|&(start, _)| start <= offset)
            .saturating_sub(1);
        match self.pieces.get(index) {
            Some(&(start, file)) => file + (offset - start),
            None => 0,
        }
    }

    /// The span in the file of `span` in the joined text. A span that runs
    /// across a continuation is cut at the end of its first piece.
    pub fn file_span(&self, span: Span) -> Span {
        let start = self.file_offset(span.start);
        let next = self
            .pieces
            .partition_point(|&(piece_start, _)| piece_start <= span.start);
        let piece_end = self
            .pieces
            .get(next)
            .map_or(self.text.len(), |&(piece_start, _)| piece_start);
        let end = self.file_offset(span.start) + (span.end.min(piece_end) - span.start);
        Span::new(start, end.max(start))
    }
}
