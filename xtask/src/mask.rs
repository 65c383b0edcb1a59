//! Timings masked out of a source's output before it is compared with the book: they are the
//! machine's, not the code's.

/// The time units a duration ends in.
const UNITS: [&str; 6] = ["ns", "µs", "us", "ms", "s", "min"];

/// `text` with every duration (`12.5 ms`, `3s`), every speed ratio (`4.5×`) and the last value
/// of each row of a table whose header ends in a time column (`… time ms`) replaced by a mark.
pub fn mask_times(text: &str) -> String {
    mask_time_columns(&mask_words(text))
}

/// Durations and ratios, glued to their unit (`12ms`, `4.5×`) or followed by it (`12.5 ms`).
fn mask_words(text: &str) -> String {
    let tokens: Vec<&str> = text.split_inclusive(char::is_whitespace).collect();
    let word = |t: &str| {
        t.trim_end()
            .trim_end_matches([',', ')', ';', '|'])
            .to_string()
    };
    let mut out = String::with_capacity(text.len());
    for (k, token) in tokens.iter().enumerate() {
        let value = word(token);
        let next = tokens.get(k + 1).map(|t| word(t)).unwrap_or_default();
        let number = |v: &str| !v.is_empty() && v.parse::<f64>().is_ok();
        let glued = UNITS
            .iter()
            .chain(&["×"])
            .any(|u| value.strip_suffix(u).is_some_and(number));
        if glued || (number(&value) && UNITS.contains(&next.as_str())) {
            out.push_str("<time>");
            out.push_str(&token[value.len()..]);
        } else {
            out.push_str(token);
        }
    }
    out
}

/// In a table whose header ends in a time column (`… time ms`, `… time s`), the last value of
/// each row, up to the next blank line, masked (with the padding before it).
fn mask_time_columns(text: &str) -> String {
    let mut timed = false;
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let words: Vec<&str> = line.split_whitespace().collect();
        if let [.., "time", "ms" | "s"] = words.as_slice() {
            timed = true;
        } else if words.is_empty() {
            timed = false;
        } else if let Some(last) = words.last().filter(|w| timed && w.parse::<f64>().is_ok()) {
            let at = line.rfind(last).unwrap_or(line.len());
            out.push_str(line[..at].trim_end());
            out.push_str(" <time>");
            out.push_str(&line[at + last.len()..]);
            continue;
        }
        out.push_str(line);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timings_are_masked_and_numbers_are_not() {
        let a = "PK 33.8 ms, QP 10.5 s | 4.5× faster, p_max 333.298 MPa, 12ms";
        let b = "PK 40.1 ms, QP 9.7 s | 5.0× faster, p_max 333.298 MPa, 15ms";
        assert_eq!(mask_times(a), mask_times(b));
        let c = "PK 40.1 ms, QP 9.7 s | 5.0× faster, p_max 333.299 MPa, 15ms";
        assert_ne!(mask_times(a), mask_times(c));
        assert_eq!(mask_times("in 57.0 ms\nnext"), "in <time> ms\nnext");
    }

    #[test]
    fn a_time_column_is_masked_to_the_next_blank_line() {
        let table =
            |t: u32, p: f64| format!("case  p_max MPa  time ms\nhertz  {p}  {t}\n\nnext 12\n");
        assert_eq!(
            mask_times(&table(109, 4536.82)),
            mask_times(&table(2051, 4536.82))
        );
        assert_ne!(
            mask_times(&table(109, 4536.82)),
            mask_times(&table(109, 4536.83))
        );
        assert!(mask_times(&table(109, 1.0)).ends_with("next 12\n"));
    }
}
