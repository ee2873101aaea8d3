//! Part files read as streams, below their format: the byte-level pieces the part-file
//! reader ([`super`]) is built on, so no part is ever held whole. Here: the
//! checksum (64-bit FNV-1a), the csv rows between line 6 and the end line
//! ([`CsvBody`]), where a json value lies in a file a json parser reads ([`Tap`]), the
//! items of a json array cut one by one ([`JsonItems`]), and bytes read again checked
//! against what was read before ([`Hashed`]). Nothing here knows a kind of file; every
//! piece hashes exactly the bytes the writer hashed.

use std::cell::{Cell, RefCell};
use std::io::{self, BufRead, Read};
use std::rc::Rc;

/// Where every checksum starts.
pub const FNV_START: u64 = 0xcbf29ce484222325;

/// 64-bit FNV-1a, continued from `h`.
pub fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x100000001b3);
    }
    h
}

fn invalid(what: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, what)
}

/// The rows of a csv part (line 7 on) as a reader, without its end line: the last line
/// that is not empty, known only at the end, so each line is handed on once the next
/// one is seen. Empty lines at the very end belong to neither; empty lines before the
/// end line are rows' bytes (the csv reader skips them). The rows' bytes are hashed and
/// counted as they pass.
pub struct CsvBody<R: BufRead> {
    input: R,
    /// The last line that is not empty (with its newline), not yet handed on.
    held: Option<Vec<u8>>,
    /// Empty lines after it.
    blanks: usize,
    line: Vec<u8>,
    out: Vec<u8>,
    out_pos: usize,
    done: bool,
    hash: u64,
    len: u64,
    longest: usize,
}

impl<R: BufRead> CsvBody<R> {
    pub fn new(input: R) -> CsvBody<R> {
        CsvBody {
            input,
            held: None,
            blanks: 0,
            line: Vec::new(),
            out: Vec::new(),
            out_pos: 0,
            done: false,
            hash: FNV_START,
            len: 0,
            longest: 0,
        }
    }

    /// The end line (after the rows have been read to their end), without its newline.
    pub fn end_line(&self) -> String {
        let held = self.held.as_deref().unwrap_or_default();
        let held = held.strip_suffix(b"\n").unwrap_or(held);
        String::from_utf8_lossy(held).into_owned()
    }

    /// The checksum of the rows' bytes.
    pub fn hash(&self) -> u64 {
        self.hash
    }

    /// Bytes of rows.
    pub fn body_len(&self) -> u64 {
        self.len
    }

    /// The longest line among the rows, in bytes.
    pub fn longest(&self) -> usize {
        self.longest
    }
}

impl<R: BufRead> Read for CsvBody<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        while self.out_pos == self.out.len() {
            if self.done {
                return Ok(0);
            }
            self.line.clear();
            if self.input.read_until(b'\n', &mut self.line)? == 0 {
                self.done = true;
                return Ok(0);
            }
            if self.line == b"\n" {
                self.blanks += 1;
                continue;
            }
            // A line that is not empty: the one held, and the empty lines after it, are
            // rows.
            self.out.clear();
            self.out_pos = 0;
            if let Some(held) = self.held.take() {
                self.longest = self.longest.max(held.len());
                self.out.extend_from_slice(&held);
            }
            self.out.extend(std::iter::repeat_n(b'\n', self.blanks));
            self.blanks = 0;
            self.held = Some(std::mem::take(&mut self.line));
            self.hash = fnv1a(self.hash, &self.out);
            self.len += self.out.len() as u64;
        }
        let n = buf.len().min(self.out.len() - self.out_pos);
        buf[..n].copy_from_slice(&self.out[self.out_pos..self.out_pos + n]);
        self.out_pos += n;
        Ok(n)
    }
}

/// What a [`Tap`] has seen, shared with the parser's visitor.
#[derive(Default)]
pub struct TapMarks {
    /// Bytes read so far.
    offset: Cell<u64>,
    /// Marking: the next byte that is not white space starts the value.
    armed: Cell<bool>,
    /// Skipping: an array that starts the value is read past by the tap itself.
    skip: Cell<bool>,
    start: Cell<Option<u64>>,
    end: Cell<Option<u64>>,
    /// Bytes of the `[]` the parser is shown in place of the array read past.
    shown: Cell<u8>,
    /// Whether an array was read past, or could not be (it is not complete).
    skipped: Cell<bool>,
    /// The array read past, as it lies in the text the parser was shown.
    cut: Cell<Option<Cut>>,
    /// What the parser was shown, when the tap keeps it (the file with the array read
    /// past as `[]`: the rest of the file, which is small).
    shown_text: RefCell<Option<Vec<u8>>>,
    /// The line (from 0) and column after the last byte shown.
    position: Cell<(usize, usize)>,
    /// The last two newlines shown: their line (from 0) and column.
    newlines: Cell<[Option<(usize, usize)>; 2]>,
}

/// An array read past: where its `[]` is in the text the parser was shown, and the
/// lines of the array in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cut {
    /// The offset of its `[]` in the text shown.
    pub at: usize,
    /// Its length in the file.
    pub len: u64,
    /// Newlines in it.
    pub newlines: usize,
    /// Bytes after its last newline (its whole length if none).
    pub tail: usize,
}

impl TapMarks {
    /// The next byte that is not JSON white space starts the value being marked; with
    /// `skip`, if that value is an array, the tap reads past it itself (fast: items are
    /// followed only as far as where they end) and shows the parser `[]` instead.
    pub fn arm(&self, skip: bool) {
        self.armed.set(true);
        self.skip.set(skip);
        self.start.set(None);
        self.end.set(None);
    }

    /// The value marked ends here: where it starts and how many bytes were read up to
    /// its end (exactly its end for an array, an object, a string or a literal; one
    /// byte more for a number, which a parser sees the end of only by the byte after
    /// it).
    pub fn disarm(&self) -> Option<(u64, u64)> {
        self.armed.set(false);
        let start = self.start.get()?;
        Some((start, self.end.get().unwrap_or(self.offset.get())))
    }

    /// Whether an array was read past (the parser's positions after it are not the
    /// file's), or could not be (the file is not a complete array there).
    pub fn skipped(&self) -> bool {
        self.skipped.get()
    }

    /// Where the value marked lies in the file (from, to), once it has been read.
    pub fn region(&self) -> Option<(u64, u64)> {
        Some((self.start.get()?, self.end.get()?))
    }

    /// The array read past, if one was read past whole.
    pub fn cut(&self) -> Option<Cut> {
        self.cut.get()
    }

    /// How long line `line` (from 1) is without its newline, if it is one of the last
    /// two lines the parser was shown whole.
    pub fn line_length(&self, line: usize) -> Option<usize> {
        let newlines = self.newlines.get();
        newlines
            .iter()
            .flatten()
            .find(|(l, _)| *l + 1 == line)
            .map(|&(_, column)| column)
    }

    /// What the parser was shown, if the tap kept it.
    pub fn shown(&self) -> Option<Vec<u8>> {
        self.shown_text.borrow().clone()
    }
}

/// A reader for a json parser that reads a byte at a time: it counts what passes and
/// marks where one value lies ([`TapMarks`]), so the value can be read again from the
/// file rather than kept; it can read past a large array itself, faster than the
/// parser, and keep what the parser was shown (to parse it again, whole, for the words
/// of a refusal).
pub struct Tap<R: BufRead> {
    input: R,
    marks: Rc<TapMarks>,
}

impl<R: BufRead> Tap<R> {
    /// A tap on `input`; with `keep`, it keeps what the parser is shown.
    pub fn new(input: R, keep: bool) -> Tap<R> {
        let marks = TapMarks::default();
        if keep {
            *marks.shown_text.borrow_mut() = Some(Vec::new());
        }
        Tap {
            input,
            marks: Rc::new(marks),
        }
    }

    /// Its marks, for the parser's visitor.
    pub fn marks(&self) -> Rc<TapMarks> {
        Rc::clone(&self.marks)
    }

    /// Read past the array that starts here, to just after its `]`.
    fn skip_array(&mut self) -> io::Result<Cut> {
        let mut scan = Scanner::new(FNV_START, usize::MAX, false);
        let m = &self.marks;
        let start = m.offset.get();
        loop {
            let buf = self.input.fill_buf()?;
            if buf.is_empty() {
                return Err(invalid("the array ends early".into()));
            }
            let (used, _) = scan.scan(buf)?;
            self.input.consume(used);
            m.offset.set(m.offset.get() + used as u64);
            if scan.state == Scan::Closed {
                let at = m.shown_text.borrow().as_ref().map_or(0, Vec::len);
                return Ok(Cut {
                    at,
                    len: m.offset.get() - start,
                    newlines: scan.line - 1,
                    tail: scan.column,
                });
            }
        }
    }

    fn show(&self, bytes: &[u8]) {
        let m = &self.marks;
        if let Some(text) = m.shown_text.borrow_mut().as_mut() {
            text.extend_from_slice(bytes);
        }
        for &b in bytes {
            let (line, column) = m.position.get();
            if b == b'\n' {
                let [_, last] = m.newlines.get();
                m.newlines.set([last, Some((line, column))]);
                m.position.set((line + 1, 0));
            } else {
                m.position.set((line, column + 1));
            }
        }
    }
}

impl<R: BufRead> Read for Tap<R> {
    #[inline]
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let m = &self.marks;
        if buf.is_empty() {
            return Ok(0);
        }
        if m.shown.get() > 0 {
            buf[0] = if m.shown.get() == 2 { b'[' } else { b']' };
            m.shown.set(m.shown.get() - 1);
            self.show(&buf[..1]);
            return Ok(1);
        }
        let avail = self.input.fill_buf()?;
        if m.armed.get() && m.start.get().is_none() {
            if let Some(&b) = avail.first() {
                if !matches!(b, b' ' | b'\t' | b'\n' | b'\r') {
                    m.start.set(Some(m.offset.get()));
                    if b == b'[' && m.skip.get() {
                        m.skipped.set(true);
                        let cut = self.skip_array()?;
                        let m = &self.marks;
                        m.cut.set(Some(cut));
                        m.end.set(Some(m.offset.get()));
                        m.shown.set(2);
                        return self.read(buf);
                    }
                }
            }
        }
        // A byte at a time while marking (the parser asks for one at a time anyway).
        let n = if m.armed.get() { 1 } else { buf.len() }.min(avail.len());
        buf[..n].copy_from_slice(&avail[..n]);
        self.input.consume(n);
        let m = &self.marks;
        m.offset.set(m.offset.get() + n as u64);
        self.show(&buf[..n]);
        Ok(n)
    }
}

/// Where an item starts in the array's text: its line (from 1) and the bytes before it
/// on that line, as a json parser of the whole array would count them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Place {
    pub line: usize,
    pub column: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scan {
    /// Before `[`.
    Open,
    /// After `[`: an item or `]`.
    First,
    /// After an item: `,` or `]`.
    After,
    /// After `,`: an item.
    Next,
    /// Inside an item.
    Item,
    /// After `]`: nothing more.
    Closed,
}

/// The items of a json array (one already checked by a json parser, read again) cut one
/// at a time out of a stream: strings, escapes and nesting followed byte by byte, every
/// byte of the array hashed (continuing from a given hash), each item at most `limit`
/// bytes. Anything that is not such an array (the file changed since) is an error.
pub struct JsonItems<R: BufRead> {
    input: R,
    scan: Scanner,
}

/// The state of a [`JsonItems`] between two bytes.
struct Scanner {
    /// Whether items are kept and bytes hashed (not when only read past).
    keep: bool,
    hash: u64,
    limit: usize,
    state: Scan,
    depth: usize,
    in_string: bool,
    escape: bool,
    line: usize,
    column: usize,
    item: Vec<u8>,
    start: Place,
    count: usize,
    longest: usize,
}

impl<R: BufRead> JsonItems<R> {
    pub fn new(input: R, hash: u64, limit: usize) -> JsonItems<R> {
        JsonItems {
            input,
            scan: Scanner::new(hash, limit, true),
        }
    }

    /// The hash, continued over every byte of the array read so far.
    pub fn hash(&self) -> u64 {
        self.scan.hash
    }

    /// Items read.
    pub fn count(&self) -> usize {
        self.scan.count
    }

    /// The longest item, in bytes.
    pub fn longest(&self) -> usize {
        self.scan.longest
    }

    /// The next item's text and where it starts, or None after `]` (and the end of the
    /// stream right after it).
    pub fn next_item(&mut self) -> io::Result<Option<(&[u8], Place)>> {
        let s = &mut self.scan;
        s.item.clear();
        loop {
            let buf = self.input.fill_buf()?;
            if buf.is_empty() {
                return match s.state {
                    Scan::Closed => Ok(None),
                    _ => Err(invalid("the array ends early".into())),
                };
            }
            let (used, done) = s.scan(buf)?;
            self.input.consume(used);
            if done {
                s.count += 1;
                s.longest = s.longest.max(s.item.len());
                return Ok(Some((&s.item, s.start)));
            }
        }
    }
}

fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r')
}

/// Bytes that change a scanner's state outside a string (and the line count).
const OUTSIDE: [bool; 256] = special(b"\"[]{},\n \t\r");
/// Bytes that change a scanner's state inside a string (and the line count).
const INSIDE: [bool; 256] = special(b"\"\\\n");

const fn special(bytes: &[u8]) -> [bool; 256] {
    let mut t = [false; 256];
    let mut i = 0;
    while i < bytes.len() {
        t[bytes[i] as usize] = true;
        i += 1;
    }
    t
}

impl Scanner {
    fn new(hash: u64, limit: usize, keep: bool) -> Scanner {
        Scanner {
            keep,
            hash,
            limit,
            state: Scan::Open,
            depth: 0,
            in_string: false,
            escape: false,
            line: 1,
            column: 0,
            item: Vec::new(),
            start: Place { line: 1, column: 0 },
            count: 0,
            longest: 0,
        }
    }

    /// Scan `buf` up to the end of an item (or of the array): the bytes taken, and whether an item ended.
    fn scan(&mut self, buf: &[u8]) -> io::Result<(usize, bool)> {
        let mut i = 0;
        while i < buf.len() {
            // Inside an item, a run of bytes that change nothing is taken at once.
            if self.state == Scan::Item && !self.escape {
                let table = if self.in_string { &INSIDE } else { &OUTSIDE };
                let run = buf[i..]
                    .iter()
                    .position(|&b| table[b as usize])
                    .unwrap_or(buf.len() - i);
                if run > 0 {
                    let bytes = &buf[i..i + run];
                    if self.keep {
                        if self.item.len() + run > self.limit {
                            return Err(invalid(format!(
                                "an item longer than {} bytes, the longest read before",
                                self.limit
                            )));
                        }
                        self.item.extend_from_slice(bytes);
                        self.hash = fnv1a(self.hash, bytes);
                    }
                    self.column += run;
                    i += run;
                    continue;
                }
            }
            let b = buf[i];
            let (take, ends) = self.step(b)?;
            if take {
                self.hash = (self.hash ^ b as u64).wrapping_mul(0x100000001b3);
                if b == b'\n' {
                    self.line += 1;
                    self.column = 0;
                } else {
                    self.column += 1;
                }
                i += 1;
            }
            if ends || self.state == Scan::Closed {
                return Ok((i, ends));
            }
        }
        Ok((i, false))
    }

    /// One byte of the array: whether it is taken (the byte that ends a number is not:
    /// it is read again after the item) and whether an item ends with it.
    fn step(&mut self, b: u8) -> io::Result<(bool, bool)> {
        let (line, column) = (self.line, self.column + 1);
        let unexpected = |what: &str| {
            Err(invalid(format!(
                "'{}' {what} at line {line} column {column}",
                b.escape_ascii()
            )))
        };
        match self.state {
            Scan::Open if b == b'[' => self.state = Scan::First,
            Scan::Open => return unexpected("where the array should start"),
            Scan::First | Scan::After | Scan::Next if is_space(b) => {}
            Scan::First | Scan::After if b == b']' => self.state = Scan::Closed,
            Scan::After if b == b',' => self.state = Scan::Next,
            Scan::After => return unexpected("after an item"),
            Scan::First | Scan::Next if matches!(b, b',' | b']') => {
                return unexpected("where an item should start")
            }
            Scan::First | Scan::Next => {
                self.state = Scan::Item;
                self.start = Place {
                    line: self.line,
                    column: self.column,
                };
                return self.item_byte(b);
            }
            Scan::Item => return self.item_byte(b),
            Scan::Closed => return unexpected("after the array"),
        }
        Ok((true, false))
    }

    fn item_byte(&mut self, b: u8) -> io::Result<(bool, bool)> {
        let mut ends = false;
        if self.in_string {
            if self.escape {
                self.escape = false;
            } else if b == b'\\' {
                self.escape = true;
            } else if b == b'"' {
                self.in_string = false;
                ends = self.depth == 0;
            }
        } else {
            match b {
                _ if self.depth == 0 && (is_space(b) || b == b',' || b == b']') => {
                    // The end of a number or literal: the byte is the array's.
                    self.state = Scan::After;
                    return Ok((false, true));
                }
                b'"' => self.in_string = true,
                b'[' | b'{' => self.depth += 1,
                b']' | b'}' if self.depth > 0 => {
                    self.depth -= 1;
                    ends = self.depth == 0;
                }
                b'}' => return Err(invalid("'}' outside any object".into())),
                _ => {}
            }
        }
        if self.keep {
            if self.item.len() >= self.limit {
                return Err(invalid(format!(
                    "an item longer than {} bytes, the longest read before",
                    self.limit
                )));
            }
            self.item.push(b);
        }
        if ends {
            self.state = Scan::After;
        }
        Ok((true, ends))
    }
}

/// Bytes read again (a part's values, between two readings of it), hashed from a given
/// hash as they pass, with no line longer than `limit` bytes (its newline counted), so
/// a file changed since it was checked cannot make its reader hold more than before.
pub struct Hashed<R: Read> {
    input: R,
    hash: u64,
    limit: usize,
    line: usize,
}

impl<R: Read> Hashed<R> {
    pub fn new(input: R, hash: u64, limit: usize) -> Hashed<R> {
        Hashed {
            input,
            hash,
            limit,
            line: 0,
        }
    }

    pub fn hash(&self) -> u64 {
        self.hash
    }
}

impl<R: Read> Read for Hashed<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.input.read(buf)?;
        let too_long = || {
            Err(invalid(format!(
                "a line longer than {} bytes, the longest read before",
                self.limit
            )))
        };
        let mut rest = &buf[..n];
        while let Some(k) = rest.iter().position(|&b| b == b'\n') {
            if self.line + k + 1 > self.limit {
                return too_long();
            }
            self.line = 0;
            rest = &rest[k + 1..];
        }
        self.line += rest.len();
        if self.line > self.limit {
            return too_long();
        }
        self.hash = fnv1a(self.hash, &buf[..n]);
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn items(text: &str) -> io::Result<(Vec<(String, Place)>, u64)> {
        let mut it = JsonItems::new(text.as_bytes(), FNV_START, 1 << 20);
        let mut out = Vec::new();
        while let Some((t, p)) = it.next_item()? {
            out.push((String::from_utf8(t.to_vec()).unwrap(), p));
        }
        Ok((out, it.hash()))
    }

    #[test]
    fn json_items_are_cut_at_the_top_level_and_every_byte_is_hashed() {
        let text = "[{\"a\":[1,\"],}\\\"\"]}, 12 ,\"x,]\" ,\n[],true,-3.5e2]";
        let (got, hash) = items(text).unwrap();
        let texts: Vec<&str> = got.iter().map(|(t, _)| t.as_str()).collect();
        assert_eq!(
            texts,
            [
                "{\"a\":[1,\"],}\\\"\"]}",
                "12",
                "\"x,]\"",
                "[]",
                "true",
                "-3.5e2"
            ]
        );
        assert_eq!(hash, fnv1a(FNV_START, text.as_bytes()));
        assert_eq!(got[3].1, Place { line: 2, column: 0 });
        let twelve = text.find("12").unwrap();
        assert_eq!(
            got[1].1,
            Place {
                line: 1,
                column: twelve
            }
        );
        assert_eq!(items("[]").unwrap().0.len(), 0);
    }

    #[test]
    fn json_items_refuse_what_is_not_one_array() {
        for bad in [
            "", "[", "[1", "[1,", "[1 2]", "[,1]", "[1,]", "{}", "[1]x", "[}]",
        ] {
            assert!(items(bad).is_err(), "{bad:?}");
        }
        let mut it = JsonItems::new("[\"abcdef\"]".as_bytes(), FNV_START, 4);
        assert!(it.next_item().is_err());
    }

    #[test]
    fn the_csv_body_leaves_out_the_end_line_and_the_empty_lines_after_it() {
        for (text, body, end) in [
            ("a\nb\n# end\n", "a\nb\n", "# end"),
            ("a\n\nb\n# end\n\n\n", "a\n\nb\n", "# end"),
            ("\na\n# end", "\na\n", "# end"),
            ("# end\n", "", "# end"),
            ("", "", ""),
            ("\n\n", "", ""),
            ("a\nb", "a\n", "b"),
        ] {
            let mut r = CsvBody::new(text.as_bytes());
            let mut got = String::new();
            r.read_to_string(&mut got).unwrap();
            assert_eq!(
                (got.as_str(), r.end_line().as_str()),
                (body, end),
                "{text:?}"
            );
            assert_eq!(r.hash(), fnv1a(FNV_START, body.as_bytes()));
            assert_eq!(r.body_len(), body.len() as u64);
        }
    }

    #[test]
    fn the_tap_marks_a_value_from_its_first_byte() {
        let text = "{\"k\":  [1, 2] }";
        let mut tap = Tap::new(text.as_bytes(), false);
        let marks = tap.marks();
        let mut b = [0u8; 1];
        for _ in 0..5 {
            tap.read_exact(&mut b).unwrap();
        }
        marks.arm(false);
        for _ in 0..8 {
            tap.read_exact(&mut b).unwrap();
        }
        assert_eq!(marks.disarm(), Some((7, 13)));
        assert_eq!(&text[7..13], "[1, 2]");
        assert!(!marks.skipped());
    }

    #[test]
    fn the_tap_can_read_past_an_array_and_show_an_empty_one() {
        let text = "{\"k\": [1, {\"a\": \"]\"}],\"z\":3}";
        let mut tap = Tap::new(text.as_bytes(), true);
        let marks = tap.marks();
        let mut seen = String::new();
        // A byte at a time, as a json parser reads.
        let byte = |tap: &mut Tap<&[u8]>| {
            let mut b = [0u8];
            (tap.read(&mut b).unwrap() == 1).then_some(b[0] as char)
        };
        for _ in 0..6 {
            seen.extend(byte(&mut tap));
        }
        marks.arm(true);
        for _ in 0..2 {
            seen.extend(byte(&mut tap));
        }
        let (start, end) = marks.disarm().unwrap();
        while let Some(c) = byte(&mut tap) {
            seen.push(c);
        }
        assert_eq!(seen, "{\"k\": [],\"z\":3}");
        assert_eq!(&text[start as usize..end as usize], "[1, {\"a\": \"]\"}]");
        assert!(marks.skipped());
        assert_eq!(marks.shown().unwrap(), seen.as_bytes());
        let cut = marks.cut().unwrap();
        assert_eq!((cut.at, cut.len, cut.newlines, cut.tail), (6, 15, 0, 15));
    }
}
