//! Reading errors, each at its file:line with what was expected and what was found, and
//! hostile input: truncated and corrupted files never panic.

use super::{committed, Msh};
use crate::Surfaces;

/// The 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle:?} not in the text"));
    text[..at].matches('\n').count() + 1
}

/// The error of reading `text`.
fn read_error(text: &str) -> String {
    crate::parse(text.as_bytes(), "t.msh")
        .unwrap_err()
        .to_string()
}

/// The two squares' text with `from` (first occurrence) replaced by `to`, and the line of
/// the replacement.
fn edited(from: &str, to: &str) -> (String, usize) {
    let text = Msh::two_squares().text();
    let line = line_of(&text, from);
    (text.replacen(from, to, 1), line)
}

/// Reading then importing: an error or a mesh, never a panic.
fn read_or_refuse(bytes: &[u8]) {
    if let Ok(gmsh) = crate::parse(bytes, "t.msh") {
        if let Ok(m) = gmsh.import(Surfaces::All) {
            for g in &m.groups {
                let _ = (m.faces(&g.name), m.nodes(&g.name));
            }
            let _ = m.check_extent([1.0, 1.0], 0.01);
        }
    }
}

/// Another version is refused with how to save 4.1.
#[test]
fn other_versions() {
    let mut msh = Msh::two_squares();
    msh.version = "2.2";
    let e = read_error(&msh.text());
    assert!(
        e.starts_with("mesh: t.msh:2: MSH version 2.2 is not read, only 4.1: save it as MSH 4.1"),
        "{e}"
    );
    assert!(
        e.contains("`gmsh -format msh41`") && e.contains("`Mesh.MshFileVersion = 4.1;`"),
        "{e}"
    );
    let e = read_error("hello\n");
    assert_eq!(
        e,
        "mesh: t.msh:1: expected `$MeshFormat` (the start of a Gmsh MSH file), found `hello`"
    );
    let e = read_error("$MeshFormat\n4.1 1 4\n");
    assert_eq!(
        e,
        "mesh: t.msh:2: expected data size 8 (a 64-bit Gmsh), found `4`"
    );
}

/// Numbers that are not numbers, or not finite, are named with their line.
#[test]
fn not_numbers() {
    let (text, line) = edited("0.5 1 0\n", "0.5 abc 0\n");
    assert_eq!(
        read_error(&text),
        format!(
            "mesh: t.msh:{line}: expected coordinate 2 of node 12 (a finite number), found `abc`"
        )
    );
    let (text, line) = edited("0.5 1 0\n", "0.5 NaN 0\n");
    assert!(read_error(&text).starts_with(&format!(
        "mesh: t.msh:{line}: expected coordinate 2 of node 12"
    )));
    let (text, line) = edited("2 1 16 2\n", "2 1 sixteen 2\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{line}: expected an element type (an integer), found `sixteen`")
    );
}

/// Counts larger than the rest of the file could hold are refused before anything is
/// allocated; a header that disagrees with its blocks is refused.
#[test]
fn huge_and_wrong_counts() {
    for (from, to, what) in [
        (
            "1 13 1 13\n",
            "1 99999999999999 1 13\n",
            "the number of nodes is 99999999999999",
        ),
        (
            "2 1 16 2\n",
            "2 1 16 18446744073709551615\n",
            "an element block's number of elements is 18446744073709551615",
        ),
        (
            "$PhysicalNames\n5\n",
            "$PhysicalNames\n5000000\n",
            "the number of physical names is 5000000",
        ),
        (
            "$Entities\n1 3 1 0\n",
            "$Entities\n1 3 1000000000 0\n",
            "the number of surfaces is 1000000000",
        ),
    ] {
        let (text, line) = edited(from, to);
        let e = read_error(&text);
        let line = line + usize::from(from.starts_with('$'));
        assert!(
            e.starts_with(&format!(
                "mesh: t.msh:{line}: {what}, more than the rest of the file could hold"
            )),
            "{e}"
        );
    }
    let (text, line) = edited("1 13 1 13\n", "1 14 1 14\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{line}: the header states 14 nodes, its blocks hold 13")
    );
}

/// Node tags: each once, within the header's range; elements refer to defined ones only.
#[test]
fn node_tags() {
    let (text, line) = edited("\n2\n3\n", "\n1\n3\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{}: node tag 1 appears twice", line + 1)
    );
    let (text, line) = edited("\n13\n", "\n14\n");
    assert_eq!(
        read_error(&text),
        format!(
            "mesh: t.msh:{}: node tag 14 is outside the range 1 ..= 13 of the header",
            line + 1
        )
    );
    let (text, line) = edited("1 1 2 5 6 7 11 12 13\n", "1 1 2 5 6 7 11 12 99\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{line}: element 1 refers to node 99, which `$Nodes` does not define")
    );
}

/// An element's nodes stay on its line: too few, too many, an unknown type.
#[test]
fn element_records() {
    let (text, line) = edited("1 1 2 5 6 7 11 12 13\n", "1 1 2 5 6 7 11 12\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{line}: expected node 8 of element 1 (type 16 (Quadrilateral 8)), found the end of the line")
    );
    let (text, line) = edited("1 1 2 5 6 7 11 12 13\n", "1 1 2 5 6 7 11 12 13 4\n");
    assert_eq!(
        read_error(&text),
        format!(
            "mesh: t.msh:{line}: expected the end of the line after the 8 nodes of element 1 \
             (type 16 (Quadrilateral 8)), found `4`"
        )
    );
    let (text, line) = edited("2 1 16 2\n", "2 1 34 2\n");
    assert_eq!(
        read_error(&text),
        format!(
            "mesh: t.msh:{line}: element type 34 is not one of Gmsh's with a fixed number of nodes"
        )
    );
    let (text, line) = edited("2 1 16 2\n", "1 1 16 2\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{line}: element type 16 (Quadrilateral 8) is 2-D, on an entity of dimension 1")
    );
}

/// Sections: others skipped, an unclosed one, `$Elements` before `$Nodes`, a partitioned
/// mesh, a name without quotes.
#[test]
fn sections() {
    let (text, _) = edited(
        "$Nodes\n",
        "$Comments\nmade by hand\n$EndComments\n$Nodes\n",
    );
    crate::parse(text.as_bytes(), "t.msh")
        .unwrap()
        .import(Surfaces::All)
        .unwrap();
    let (text, line) = edited("$Nodes\n", "$Comments\nmade by hand\n");
    assert_eq!(
        read_error(&text),
        format!("mesh: t.msh:{line}: `$Comments` has no `$EndComments`")
    );
    let msh = Msh::two_squares().text();
    let (nodes, elements) = (msh.find("$Nodes").unwrap(), msh.find("$Elements").unwrap());
    let swapped = format!(
        "{}{}{}",
        &msh[..nodes],
        &msh[elements..],
        &msh[nodes..elements]
    );
    let line = line_of(&swapped, "$Elements");
    assert_eq!(
        read_error(&swapped),
        format!("mesh: t.msh:{line}: `$Elements` before `$Nodes`")
    );
    let (text, line) = edited(
        "$Nodes\n",
        "$PartitionedEntities\n$EndPartitionedEntities\n$Nodes\n",
    );
    assert!(read_error(&text).starts_with(&format!("mesh: t.msh:{line}: a partitioned mesh")));
    let (text, line) = edited("\"top\"", "top");
    assert_eq!(
        read_error(&text),
        format!(
            "mesh: t.msh:{line}: expected a physical group's name in double quotes, found `top`"
        )
    );
}

/// Every prefix of a file, and the file with any byte replaced, reads or is refused: never a
/// panic. Refusals of a cut file name it.
#[test]
fn truncated_and_corrupted_text() {
    let text = Msh::two_squares().text();
    let bytes = text.as_bytes();
    for end in 0..bytes.len() {
        read_or_refuse(&bytes[..end]);
        if let Err(e) = crate::parse(&bytes[..end], "t.msh") {
            assert!(e.to_string().starts_with("mesh: t.msh:"), "{e}");
        }
    }
    for k in 0..bytes.len() {
        for b in [b'x', b'9', b'-', b' ', b'\n', b'"', b'$', 0xFF] {
            let mut bad = bytes.to_vec();
            bad[k] = b;
            read_or_refuse(&bad);
        }
    }
}

/// The same for a binary file Gmsh wrote (every 7th prefix, every 7th byte inverted), and a
/// count patched past the file's size is refused with its byte.
#[test]
fn truncated_and_corrupted_binary() {
    let path = format!(
        "{}/../../meshes/rectangle-q8-binary.msh",
        env!("CARGO_MANIFEST_DIR")
    );
    let bytes = std::fs::read(path).unwrap();
    for end in (0..bytes.len()).step_by(7) {
        read_or_refuse(&bytes[..end]);
    }
    for k in (0..bytes.len()).step_by(7) {
        let mut bad = bytes.clone();
        bad[k] = !bad[k];
        read_or_refuse(&bad);
    }
    let nodes = bytes.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
    let mut bad = bytes.clone();
    bad[nodes + 8..nodes + 16].copy_from_slice(&(1u64 << 40).to_le_bytes());
    let e = crate::parse(&bad, "b.msh").unwrap_err().to_string();
    assert!(
        e.contains(&format!(
            "(byte {}): the number of nodes is 1099511627776, more than",
            nodes + 8
        )),
        "{e}"
    );
    assert!(committed("rectangle-q8-binary.msh").is_binary());
}

/// A file that cannot be read is named with the system's reason.
#[test]
fn unreadable_file() {
    let e = crate::read("no/such/mesh.msh").unwrap_err().to_string();
    assert!(
        e.starts_with("invalid mesh file = no/such/mesh.msh: "),
        "{e}"
    );
}
