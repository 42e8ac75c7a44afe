//! The field at a place in a JSON text, for a reader's error: JSON's reader says "invalid
//! type: string "a", expected f64 at line 1 column 45", and a person wants to read
//! `joints[0].at[1]`. The text is scanned up to that place, keeping the keys and indices of
//! the objects and arrays open there.

/// One open object or array.
enum Open {
    /// An object, with the key of the member being read (once read), and whether a key comes
    /// next (after `{` or `,`).
    Object {
        key: Option<String>,
        expect_key: bool,
    },
    /// An array, with the index of the element being read.
    Array(usize),
}

/// The path of the field at `line` and `column` (as JSON's reader counts them: from 1, the
/// column in bytes) of `text`: `joints[0].at[1]`; empty at the top level.
pub fn path_at(text: &str, line: usize, column: usize) -> String {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let end = (start + column).min(text.len());
    let bytes = &text.as_bytes()[..end];
    let mut open: Vec<Open> = Vec::new();
    let mut k = 0;
    while k < bytes.len() {
        match bytes[k] {
            b'{' => open.push(Open::Object {
                key: None,
                expect_key: true,
            }),
            b'[' => open.push(Open::Array(0)),
            b'}' | b']' => {
                open.pop();
            }
            b',' => match open.last_mut() {
                Some(Open::Array(i)) => *i += 1,
                Some(Open::Object { key, expect_key }) => {
                    *key = None;
                    *expect_key = true;
                }
                None => {}
            },
            b':' => {
                if let Some(Open::Object { expect_key, .. }) = open.last_mut() {
                    *expect_key = false;
                }
            }
            b'"' => {
                // A string, to its closing quote (a backslash escapes the byte after it).
                let from = k + 1;
                k = from;
                while k < bytes.len() && bytes[k] != b'"' {
                    k += if bytes[k] == b'\\' { 2 } else { 1 };
                }
                if let Some(Open::Object {
                    key,
                    expect_key: true,
                }) = open.last_mut()
                {
                    *key = Some(String::from_utf8_lossy(&bytes[from..k.min(bytes.len())]).into());
                }
            }
            _ => {}
        }
        k += 1;
    }
    let mut path = String::new();
    for o in &open {
        match o {
            Open::Object { key: Some(key), .. } => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(key);
            }
            Open::Object { key: None, .. } => {}
            Open::Array(i) => path.push_str(&format!("[{i}]")),
        }
    }
    path
}

#[cfg(test)]
mod tests {
    use super::path_at;

    #[test]
    fn the_path_at_a_place_names_its_keys_and_indices() {
        let text = "{\"name\": \"x\",\n \"joints\": [{\"name\": \"A\", \"at\": [0, \"a\"]}]}";
        // Line 2, just after "a" (the column JSON's reader gives for that error).
        let col = text.lines().nth(1).unwrap().find("\"a\"").unwrap() + 3;
        assert_eq!(path_at(text, 2, col), "joints[0].at[1]");
        assert_eq!(path_at(text, 1, 8), "name");
        assert_eq!(
            path_at("{\"a\": {\"b\\\"c\": [1, [2, 3", 1, 24),
            "a.b\\\"c[1][1]"
        );
        assert_eq!(path_at("[1, 2]", 1, 2), "[0]");
        assert_eq!(path_at("", 1, 0), "");
    }
}
