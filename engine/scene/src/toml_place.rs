//! Where a key of level.toml is written, for the errors found after parsing: a value out of
//! range is only known once the file has been read into the schema, which keeps no positions.

use toml_edit::{ImDocument, TableLike};

use crate::error::TextPos;

/// The place of a dotted key such as `headlamp.power`, `lights[2].intensity` or `lights[2]`
/// (the key's first character; for an entry of an array of tables, its header). A key the
/// text lacks is placed at the deepest part that is there (`lights[0].position` of a light
/// without one: its `[[lights]]` header); None when not even the first part is.
pub fn key_place(text: &str, key: &str) -> Option<TextPos> {
    let doc = ImDocument::parse(text).ok()?;
    let mut table: &dyn TableLike = doc.as_table();
    let mut place = None;
    for part in key.split('.') {
        let (name, index) = split_index(part);
        let Some((k, item)) = table.get_key_value(name) else { break };
        place = k.span().map(|s| s.start).or(place);
        let next: Option<&dyn TableLike> = match index {
            None => item.as_table_like(),
            Some(i) => {
                if let Some(entry) = item.as_array_of_tables().and_then(|a| a.get(i)) {
                    place = entry.span().map(|s| s.start).or(place);
                    Some(entry)
                } else if let Some(entry) = item.as_array().and_then(|a| a.get(i)) {
                    place = entry.span().map(|s| s.start).or(place);
                    entry.as_inline_table().map(|t| t as &dyn TableLike)
                } else {
                    None
                }
            }
        };
        match next {
            Some(t) => table = t,
            None => break,
        }
    }
    place.map(|offset| TextPos::of_offset(text, offset))
}

/// `lights[2]` → (`lights`, Some(2)); `power` → (`power`, None).
fn split_index(part: &str) -> (&str, Option<usize>) {
    match part.strip_suffix(']').and_then(|p| p.split_once('[')) {
        Some((name, index)) => (name, index.parse().ok()),
        None => (part, None),
    }
}

/// The dotted key a value check's message starts with: every such message in
/// `level_toml.rs` names its key first (`lights[0].outer_deg (35) must be ...`).
pub(crate) fn leading_key(message: &str) -> &str {
    let end = message
        .find(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '[' | ']')))
        .unwrap_or(message.len());
    message[..end].trim_end_matches('.')
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "name = \"L\"\nscene = \"s.obj\"\n\n[headlamp]\npower = -1\n\n[[lights]]\nkind = \"point\"\n\n[[lights]]\nkind = \"spot\"\n  outer_deg = 3\n";

    fn at(line: usize, column: usize) -> Option<TextPos> {
        Some(TextPos { line, column })
    }

    #[test]
    fn keys_tables_and_array_entries_are_placed() {
        assert_eq!(key_place(TEXT, "scene"), at(2, 1));
        assert_eq!(key_place(TEXT, "headlamp.power"), at(5, 1));
        assert_eq!(key_place(TEXT, "lights[1].outer_deg"), at(12, 3));
        assert_eq!(key_place(TEXT, "lights[0].position"), at(7, 1), "missing: the entry's header");
        assert_eq!(key_place(TEXT, "spawn.position"), None);
        assert_eq!(key_place("lights = [{kind = \"point\"}, {kind = 3}]", "lights[1].kind"), at(1, 30));
        assert_eq!(key_place("not toml = = 3", "name"), None);
    }

    #[test]
    fn messages_start_with_their_key() {
        assert_eq!(leading_key("lights[0].outer_deg (35) must be greater"), "lights[0].outer_deg");
        assert_eq!(leading_key("lights[0]: a point light needs a position"), "lights[0]");
        assert_eq!(leading_key("name must not be empty"), "name");
        assert_eq!(leading_key("spawn.position [NaN, 0.0, 0.0] must be finite"), "spawn.position");
    }
}
