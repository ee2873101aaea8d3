//! A json part read and checked: a json parser checks the whole file but for the large
//! array of values, which is marked where it lies and read again item by item; a file
//! that is not complete json is parsed again so the refusal is the whole-file parser's.

use super::stream::{JsonItems, Place, Tap, TapMarks};
use super::tally::{Reading, Tally};
use super::*;

/// Read a json part. A json parser checks the whole file but for a large array of
/// values, which is only read past ([`Tap`]) and then read again and checked item by
/// item; a file that is not complete json where that shortcut was taken (after the
/// array, or inside it) is parsed again byte by byte, so the refusal is the one a
/// parser of the whole file gives, word for word.
pub(super) fn read_json<K: FileKind, R: BufRead>(
    name: &str,
    input: R,
    again: &mut Again,
) -> Result<Reading<K>, String> {
    if let Some(reading) = parse_json::<K, R>(name, input, again, true)? {
        return Ok(reading);
    }
    let whole = again(0, u64::MAX).map_err(|e| format!("cannot read: {e}"))?;
    parse_json::<K, _>(name, whole, again, false)?.ok_or_else(|| {
        format!(
            "its {} changed while being read (their json differs from the first reading)",
            K::UNIT
        )
    })
}

/// [`read_json`], the array of values read past by the tap (`skip`) or by the parser;
/// None when the file is not complete json and only a parser reading the whole file
/// byte by byte can say where.
fn parse_json<K: FileKind, R: BufRead>(
    name: &str,
    input: R,
    again: &mut Again,
    skip: bool,
) -> Result<Option<Reading<K>>, String> {
    let tap = Tap::new(input, skip);
    let marks = tap.marks();
    let mut de = serde_json::Deserializer::from_reader(tap);
    let parsed = de
        .deserialize_map(JsonVisitor::<K> {
            marks: Some(&marks),
            skip,
            kind: PhantomData,
        })
        .and_then(|p| de.end().map(|()| p));
    let p = match parsed {
        Ok(p) => p,
        Err(e) if !skip => return Err(incomplete::<K>(&as_whole(&e, &marks))),
        Err(_) => return refusal::<K>(&marks, again).map(|()| None),
    };
    let shard = parse_shard(&p.provenance.shard);
    let mut tally = Tally::<K>::new(&p.header, shard.clone().unwrap_or(None));
    let start = p
        .sections
        .iter()
        .fold(FNV_START, |h, s| fnv1a(h, s.get().as_bytes()));
    // The values, read again: their checksum, each value parsed and checked in turn.
    let (offset, end) = p.values;
    let changed = |e: io::Error| {
        format!(
            "its {} changed while being read ({})",
            K::UNIT,
            one_line(&e.to_string())
        )
    };
    let mut region = again(offset, end - offset).map_err(changed)?;
    let (hash, malformed, longest) = if region.fill_buf().map_err(changed)?.first() == Some(&b'[') {
        let mut items = JsonItems::new(region, start, usize::MAX);
        let mut malformed = None;
        while let Some((text, at)) = items.next_item().map_err(changed)? {
            if malformed.is_none() {
                match serde_json::from_slice::<K::Item>(text) {
                    Ok(item) => {
                        tally.value(&K::from_item(item));
                        continue;
                    }
                    Err(e) => malformed = Some(placed(&e, at)),
                }
            }
            // An item that is not json at all: what a parser of the whole file says.
            if let Err(e) = serde_json::from_slice::<de::IgnoredAny>(text) {
                return item_refusal::<K>(&e, at, &marks).map(|()| None);
            }
        }
        (items.hash(), malformed, items.longest())
    } else {
        let (hash, why) = not_an_array::<K>(region, end - offset, start).map_err(changed)?;
        (hash, Some(why), 0)
    };
    if format!("{hash:016x}") != p.checksum {
        return Err(format!(
            "its {} do not match their checksum {} (damaged?)",
            K::UNIT,
            clip(&p.checksum)
        ));
    }
    if let Some(why) = malformed {
        return Err(format!("malformed {} ({why})", K::UNIT));
    }
    let shard = shard?;
    if p.file.as_deref().is_some_and(|f| f != K::KIND) {
        return Err(format!("not a {} file", K::KIND));
    }
    let count = tally.count;
    let part = Part {
        name: name.to_string(),
        layout: Layout::Json,
        provenance: p.provenance,
        header: p.header,
        shard,
        sections: p.sections.iter().map(|s| s.get().to_string()).collect(),
        count,
        body: Body {
            offset,
            len: end - offset,
            start,
            hash,
            rows: count,
            longest,
        },
    };
    Ok(Some((part, tally.result())))
}

/// A json parser's message about one item, placed in the text of the whole array as a
/// parser of the array would place it (line 1 column 1 is the `[`).
fn placed(e: &serde_json::Error, at: Place) -> String {
    let msg = e.to_string();
    if e.line() == 0 {
        return one_line(&msg);
    }
    let (line, column) = if e.line() == 1 {
        (at.line, at.column + e.column())
    } else {
        (at.line + e.line() - 1, e.column())
    };
    one_line(&at_position(e, line, column))
}

/// A json parser's message as a parser holding the whole text gives it: a control
/// character in a string is placed before it, not after it (a parser reading a stream
/// has read it by then).
fn as_whole(e: &serde_json::Error, marks: &TapMarks) -> String {
    if !e.to_string().starts_with("control character") || e.line() == 0 {
        return e.to_string();
    }
    if e.column() > 0 {
        return at_position(e, e.line(), e.column() - 1);
    }
    // The character was a newline: the end of the line before.
    match marks.line_length(e.line() - 1) {
        Some(column) => at_position(e, e.line() - 1, column),
        None => e.to_string(),
    }
}

/// The refusal of a json part that is not complete json.
fn incomplete<K: FileKind>(why: &str) -> String {
    format!("not a complete {} json file ({})", K::KIND, one_line(why))
}

/// Why a json part whose array of values was read past by the tap is not complete json,
/// in the words of a parser of the whole file: the text the parser was shown (the file,
/// the array as `[]`), parsed again whole, its position moved back over the array, unless
/// an item of the array comes first that is not json. `Ok` when only a parser reading
/// the whole file byte by byte can say (the array itself is not complete).
fn refusal<K: FileKind>(marks: &TapMarks, again: &mut Again) -> Result<(), String> {
    let Some(shown) = marks.shown() else {
        return Ok(());
    };
    let cut = marks.cut();
    if marks.skipped() && cut.is_none() {
        return Ok(());
    }
    let mut de = serde_json::Deserializer::from_slice(&shown);
    let again_parsed = de
        .deserialize_map(JsonVisitor::<K> {
            marks: None,
            skip: false,
            kind: PhantomData,
        })
        .and_then(|_| de.end());
    let Err(e) = again_parsed else {
        return Ok(());
    };
    let (Some(cut), Some((from, to))) = (cut, marks.region()) else {
        return Err(incomplete::<K>(&e.to_string()));
    };
    let (line, column) = place_in(&shown, cut.at);
    let after = e.line() > line || (e.line() == line && e.column() >= column + 2);
    if after {
        // The array comes first: any item in it that is not json is what is said.
        let region = again(from, to - from).map_err(|e| format!("cannot read: {e}"))?;
        let mut items = JsonItems::new(region, FNV_START, usize::MAX);
        loop {
            match items.next_item() {
                Ok(Some((text, at))) => {
                    if let Err(e) = serde_json::from_slice::<de::IgnoredAny>(text) {
                        return item_refusal::<K>(&e, at, marks);
                    }
                }
                Ok(None) => break,
                Err(_) => return Ok(()),
            }
        }
    }
    let moved = if !after || e.line() == 0 {
        e.to_string()
    } else {
        let column = if e.line() != line {
            e.column()
        } else if cut.newlines == 0 {
            e.column() - 2 + cut.len as usize
        } else {
            e.column() - 2 - column + cut.tail
        };
        at_position(&e, e.line() + cut.newlines, column)
    };
    Err(incomplete::<K>(&moved))
}

/// Why a json part with an item of values that is not json is refused, in the words of
/// a parser of the whole file (the item parsed alone, its position moved to the
/// file's); `Ok` when the item alone may not fail as the whole would (it ends early, or
/// is followed by more): a parser reading the whole file byte by byte says then.
fn item_refusal<K: FileKind>(
    e: &serde_json::Error,
    at: Place,
    marks: &TapMarks,
) -> Result<(), String> {
    let (Some(shown), Some(cut)) = (marks.shown(), marks.cut()) else {
        return Ok(());
    };
    if e.is_eof() || e.to_string().starts_with("trailing characters") {
        return Ok(());
    }
    let (line, column) = place_in(&shown, cut.at);
    let at = Place {
        line: line + at.line - 1,
        column: if at.line == 1 {
            column + at.column
        } else {
            at.column
        },
    };
    Err(incomplete::<K>(&placed(e, at)))
}

/// The line (from 1) and the bytes before it on its line of offset `at` of `text`.
fn place_in(text: &[u8], at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |k| k + 1);
    (
        1 + before[..start].iter().filter(|&&b| b == b'\n').count(),
        before.len() - start,
    )
}

/// A json parser's message with its position replaced.
fn at_position(e: &serde_json::Error, line: usize, column: usize) -> String {
    let msg = e.to_string();
    let bare = msg
        .strip_suffix(&format!(" at line {} column {}", e.line(), e.column()))
        .unwrap_or(&msg);
    format!("{bare} at line {line} column {column}")
}

/// The checksum of values that are not an array, and why they are malformed, as the
/// parser of a whole array says it (read whole only up to a MiB: more than that which
/// is not an array is malformed without a closer look).
fn not_an_array<K: FileKind>(
    region: impl BufRead,
    len: u64,
    start: u64,
) -> io::Result<(u64, String)> {
    const LOOK: u64 = 1 << 20;
    if len > LOOK {
        return Ok((start, "not an array".into()));
    }
    let mut bytes = Vec::new();
    region.take(LOOK).read_to_end(&mut bytes)?;
    // The stretch read may end one byte after a number: the value is what a parser
    // takes of it.
    let mut de = serde_json::Deserializer::from_slice(&bytes);
    let raw = <&RawValue>::deserialize(&mut de).map_err(io::Error::other)?;
    let why = match serde_json::from_str::<Vec<K::Item>>(raw.get()) {
        Ok(_) => "not an array".to_string(),
        Err(e) => one_line(&e.to_string()),
    };
    Ok((fnv1a(start, raw.get().as_bytes()), why))
}

/// The json layout as read: the provenance, the settings (every other key), the
/// sections before the values as their raw text, where the values are (from, to) and
/// the checksum.
struct JsonPart<K: FileKind> {
    provenance: Provenance,
    /// The kind the file names (`file`), if it names one.
    file: Option<String>,
    header: K::Header,
    sections: Vec<Box<RawValue>>,
    values: (u64, u64),
    checksum: String,
}

/// Reads the json layout, the values only marked where they are (an array of them
/// read past by the tap, with `skip`).
struct JsonVisitor<'m, K> {
    /// None: the values are only checked as json (a second parse, for its words).
    marks: Option<&'m TapMarks>,
    skip: bool,
    kind: PhantomData<K>,
}

impl<'de, K: FileKind> Visitor<'de> for JsonVisitor<'_, K> {
    type Value = JsonPart<K>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a {} file", K::KIND)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut provenance = None;
        let mut checksum: Option<String> = None;
        let last = K::SECTIONS.len() - 1;
        let mut sections: Vec<Option<Box<RawValue>>> = vec![None; last];
        let mut values: Option<(u64, u64)> = None;
        let mut settings = serde_json::Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if key == "provenance" {
                once(&provenance, "provenance")?;
                provenance = Some(map.next_value_seed(ProvenanceSeed::<K>(PhantomData))?);
            } else if key == "checksum" {
                once(&checksum, "checksum")?;
                checksum = Some(map.next_value()?);
            } else if let Some(k) = K::SECTIONS.iter().position(|s| *s == key) {
                if k == last {
                    once(&values, K::SECTIONS[k])?;
                    values = Some(match self.marks {
                        Some(marks) => map.next_value_seed(Marked(marks, self.skip))?,
                        None => map.next_value::<de::IgnoredAny>().map(|_| (0, 0))?,
                    });
                } else {
                    once(&sections[k], K::SECTIONS[k])?;
                    sections[k] = Some(map.next_value()?);
                }
            } else {
                let value: serde_json::Value = map.next_value()?;
                settings.insert(key, value);
            }
        }
        let (provenance, file) =
            provenance.ok_or_else(|| de::Error::missing_field("provenance"))?;
        let header = K::Header::deserialize(serde_json::Value::Object(settings))
            .map_err(de::Error::custom)?;
        let sections = sections
            .into_iter()
            .zip(K::SECTIONS)
            .map(|(s, name)| s.ok_or_else(|| de::Error::missing_field(name)))
            .collect::<Result<_, _>>()?;
        let values = values.ok_or_else(|| de::Error::missing_field(K::SECTIONS[last]))?;
        Ok(JsonPart {
            provenance,
            file,
            header,
            sections,
            values,
            checksum: checksum.ok_or_else(|| de::Error::missing_field("checksum"))?,
        })
    }
}

/// Any json value, checked as json and skipped (an array, with `skip`, read past by the
/// tap); where it lies is marked by the tap.
struct Marked<'m>(&'m TapMarks, bool);

impl<'de> DeserializeSeed<'de> for Marked<'_> {
    type Value = (u64, u64);

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        self.0.arm(self.1);
        de::IgnoredAny::deserialize(d)?;
        self.0
            .disarm()
            .ok_or_else(|| de::Error::custom("a value without a first byte"))
    }
}

/// A field seen a second time is refused.
fn once<T, E: de::Error>(slot: &Option<T>, name: &'static str) -> Result<(), E> {
    match slot {
        Some(_) => Err(E::duplicate_field(name)),
        None => Ok(()),
    }
}

/// Reads a json provenance of kind `K` (exactly its keys), with the kind it names.
struct ProvenanceSeed<K>(PhantomData<K>);

impl<'de, K: FileKind> DeserializeSeed<'de> for ProvenanceSeed<K> {
    type Value = (Provenance, Option<String>);

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_struct("Provenance", K::PROVENANCE, self)
    }
}

impl<'de, K: FileKind> Visitor<'de> for ProvenanceSeed<K> {
    type Value = (Provenance, Option<String>);

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("struct Provenance")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let (mut file, mut tool, mut spec_hash, mut shard) = (None, None, None, None);
        let mut count: Option<usize> = None;
        while let Some(key) = map.next_key::<String>()? {
            let Some(&known) = K::PROVENANCE.iter().find(|k| **k == key) else {
                return Err(de::Error::unknown_field(&key, K::PROVENANCE));
            };
            let slot: &mut Option<String> = match known {
                "file" => &mut file,
                "tool" => &mut tool,
                "spec_hash" => &mut spec_hash,
                "shard" => &mut shard,
                _ => {
                    once(&count, known)?;
                    count = Some(map.next_value()?);
                    continue;
                }
            };
            once(slot, known)?;
            *slot = Some(map.next_value()?);
        }
        // Missing keys are named in the order the file states them.
        if K::PROVENANCE.contains(&"file") && file.is_none() {
            return Err(de::Error::missing_field("file"));
        }
        let missing = de::Error::missing_field;
        let provenance = Provenance {
            tool: tool.ok_or_else(|| missing("tool"))?,
            spec_hash: spec_hash.ok_or_else(|| missing("spec_hash"))?,
            shard: shard.ok_or_else(|| missing("shard"))?,
            count: count.ok_or_else(|| missing(K::UNIT))?,
        };
        Ok((provenance, file))
    }
}
