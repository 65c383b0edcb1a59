//! Many cases: a scene run on two threads writes the files a run on one writes, and run as four
//! shards (`contopt run --shard K/4`, as four tasks of a Slurm array would) and merged
//! (`contopt merge`) too, byte for byte but the timings; bad shards and bad sets of shards are
//! refused, naming the value.

use crate::common;

use std::path::{Path, PathBuf};

use common::{bundled, contopt, fails_with, read_json, scratch, stderr, write_scene};

/// This binary's scratch folders.
const BIN: &str = "many_cases";

/// The Hertz scene on a coarser grid under five loads: five cases, so four shards hold two,
/// one, one and one; each writes a pressure map, a section's stresses (CSV and map) beside the
/// scene's files.
fn sweep() -> String {
    let text = bundled(
        "hertz",
        &[
            ("name = \"hertz\"", "name = \"hertz-loads\""),
            (
                "cells = [64, 64], cell_mm = [0.0125, 0.0125]",
                "cells = [32, 32], cell_mm = [0.025, 0.025]",
            ),
            ("depths = 60", "depths = 12"),
        ],
    );
    text + "\n[sweep]\nkey = \"contact.load.force_n\"\nvalues = [500.0, 750.0, 1000.0, \
            1250.0, 1500.0]\n"
}

/// `contopt <args>`, which must succeed.
fn ok(args: &[&std::ffi::OsStr]) {
    let output = contopt().args(args).output().unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

/// The files of two results folders are the same, in the same order (as their manifests list
/// them), byte for byte but result.json's timings.
fn assert_same_files(whole: &Path, other: &Path) -> Vec<String> {
    let names = listed(whole);
    assert_eq!(listed(other), names);
    for name in &names {
        let (a, b) = (whole.join(name), other.join(name));
        if name == "result.json" {
            assert_eq!(untimed(&a), untimed(&b), "result.json");
        } else {
            let same = std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap();
            assert!(
                same,
                "{name} differs between {} and {}",
                whole.display(),
                other.display()
            );
        }
    }
    names
}

/// `contopt run <scene> --quiet --out <out> <more…>`, which must succeed.
fn run(scene: &Path, out: &Path, more: &[&str]) {
    let output = contopt()
        .arg("run")
        .arg(scene)
        .args(["--quiet", "--out"])
        .arg(out)
        .args(more)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

/// Each of `scenes` (its file, its name and a file its run must write) run on one thread and on
/// two into `dir`: the two runs write the same files, byte for byte.
fn one_and_two_threads_agree(dir: &Path, scenes: &[(&Path, &str, &str)]) {
    let (one, two) = (dir.join("one"), dir.join("two"));
    for (scene, _, _) in scenes {
        run(scene, &one, &["--jobs", "1"]);
        run(scene, &two, &["--jobs", "2"]);
    }
    for (_, name, file) in scenes {
        let names = assert_same_files(&one.join(name), &two.join(name));
        assert!(names.iter().any(|n| n == file), "{names:?}");
    }
}

/// Two threads give what one gives, to the bit: five cases of different loads (five builds)
/// run two at a time, and three cases on one pair of bodies (one build on one thread, two on
/// two).
#[test]
fn two_threads_write_what_one_writes() {
    let dir = scratch(BIN, "threads");
    let loads = write_scene(&dir, "hertz-loads", &sweep());
    let shared = sweep()
        .replace("name = \"hertz-loads\"", "name = \"hertz-depths\"")
        .replace("contact.load.force_n", "output.subsurface.depths")
        .replace("[500.0, 750.0, 1000.0, 1250.0, 1500.0]", "[8, 10, 12]");
    let depths = write_scene(&dir, "hertz-depths", &shared);
    one_and_two_threads_agree(
        &dir,
        &[
            (&loads, "hertz-loads", "subsurface_5.csv"),
            (&depths, "hertz-depths", "mises_3_1.svg"),
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The roller envelope on a coarse grid (40 × 21 cells), its nine load cases under each crown
/// solved at once: the ISO crown's envelope, the Fujiwara–Kawase search (the nine under every
/// crown it tries) and the robust crown's envelope split; `labels` chooses the cases.
fn envelope(name: &str, labels: &[&str]) -> String {
    let text = bundled(
        "roller-envelope",
        &[
            ("name = \"roller-envelope\"", &format!("name = \"{name}\"")),
            ("cells = [200, 105]", "cells = [40, 21]"),
        ],
    );
    let (head, cases) = text.split_at(text.find("[[case]]").unwrap());
    let chosen: Vec<&str> = cases
        .split_inclusive("\n\n")
        .filter(|case| {
            labels
                .iter()
                .any(|l| case.contains(&format!("label = \"{l}")))
        })
        .collect();
    assert_eq!(chosen.len(), labels.len(), "{labels:?}");
    head.to_string() + &chosen.concat()
}

/// Two threads solve a case's independent contacts (an envelope's nine cases under a crown)
/// as one does, to the bit: one case alone has both threads for its envelope split, and three
/// cases on one pair of bodies share them with the search.
#[test]
fn two_threads_solve_an_envelope_as_one() {
    let dir = scratch(BIN, "envelope");
    let robust = envelope("robust", &["robust, L1 = 5"]);
    let three = envelope("three", &["ISO", "Fujiwara", "robust, L1 = 5"]);
    let (robust, three) = (
        write_scene(&dir, "robust", &robust),
        write_scene(&dir, "three", &three),
    );
    one_and_two_threads_agree(
        &dir,
        &[
            (&robust, "robust", "envelope_1.svg"),
            (&three, "three", "p_map_3.svg"),
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs shard `k` of `n` of `scene` into `out`.
fn shard(scene: &Path, k: usize, n: usize, out: &Path) {
    run(scene, out, &["--shard", &format!("{k}/{n}")]);
}

/// The files a run listed in its folder's manifest, in order.
fn listed(folder: &Path) -> Vec<String> {
    let manifest = std::fs::read_to_string(folder.join(".contopt-results")).unwrap();
    manifest.lines().map(str::to_string).collect()
}

/// The text of a `result.json` with every stage's time left out (the keys kept): the rest of
/// the text as written, so that numbers must agree in every digit.
fn untimed(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let mut inside = false;
    let mut kept = String::new();
    for line in text.lines() {
        if inside && line.trim_start().starts_with('}') {
            inside = false;
        }
        let line = match line.split_once(':') {
            Some((key, _)) if inside => key,
            _ => line,
        };
        if line.trim_end().ends_with("\"timings_ms\": {") {
            inside = true;
        }
        kept += line;
        kept += "\n";
    }
    assert!(
        !inside && kept.contains("\"timings_ms\": {"),
        "{}",
        path.display()
    );
    kept
}

/// Four shards merged are one run: the same files in the same order, each byte for byte
/// (result.json once its timings are zeroed), the shard folders left beside them.
#[test]
fn four_shards_merge_into_one_run() {
    let dir = scratch(BIN, "four");
    let scene = write_scene(&dir, "hertz-loads", &sweep());
    let one = dir.join("one");
    run(&scene, &one, &[]);
    let sharded = dir.join("sharded");
    for k in [3, 1, 0, 2] {
        shard(&scene, k, 4, &sharded);
    }
    let shards = sharded.join("hertz-loads");
    assert_eq!(listed(&shards.join("shard_0_of_4"))[0], "partial.json");
    ok(&[
        "merge".as_ref(),
        shards.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        sharded.as_os_str(),
    ]);
    let names = assert_same_files(&one.join("hertz-loads"), &shards);
    for name in ["p_map_5.svg", "subsurface_5.csv", "mises_5_1.png", "p.svg"] {
        assert!(names.iter().any(|n| n == name), "{name} not in {names:?}");
    }
    assert!(shards.join("shard_3_of_4/partial.json").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `contopt merge <folders…> --out <out>`: the output.
fn merge(folders: &[PathBuf], out: &Path) -> std::process::Output {
    contopt()
        .arg("merge")
        .args(folders)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// A shard K ≥ N or of N = 0 is a usage error naming the value; shards missing, given twice,
/// of another scene or of another version of the scene are refused naming the shard, the
/// scenes, the fingerprints; a folder without shards says what to give.
#[test]
fn bad_shards_are_refused() {
    let dir = scratch(BIN, "bad");
    let scene = write_scene(&dir, "hertz-loads", &sweep());
    for (spec, says) in [
        ("4/4", "K = 4 is not below N = 4"),
        ("0/0", "N = 0"),
        ("2", "write the shard as K/N"),
    ] {
        let output = contopt()
            .arg("run")
            .arg(&scene)
            .args(["--shard", spec])
            .output()
            .unwrap();
        fails_with(&output, 2, &[&format!("'{spec}'"), says]);
    }
    // Two shards of five cases split as 0..2, 2..5; a third "version" changes one load.
    let out = dir.join("out");
    shard(&scene, 0, 2, &out);
    let folder = |k: usize| out.join(format!("hertz-loads/shard_{k}_of_2"));
    let output = merge(&[folder(0)], &dir.join("merged"));
    fails_with(&output, 1, &["shard 1/2 of scene hertz-loads missing"]);
    let output = merge(&[folder(0), folder(0)], &dir.join("merged"));
    fails_with(&output, 1, &["shard 0/2 is given twice"]);

    let changed = write_scene(&dir, "changed", &sweep().replace("1250.0", "1200.0"));
    shard(&changed, 1, 2, &out);
    let output = merge(&[folder(0), folder(1)], &dir.join("merged"));
    let fingerprint = |k: usize| read_json(&folder(k).join("partial.json"))["fingerprint"].clone();
    let (a, b) = (fingerprint(1), fingerprint(0));
    fails_with(
        &output,
        1,
        &[
            "different versions of scene hertz-loads",
            a.as_str().unwrap(),
            b.as_str().unwrap(),
        ],
    );
    let other = write_scene(
        &dir,
        "other",
        &sweep().replace("name = \"hertz-loads\"", "name = \"other\""),
    );
    shard(&other, 1, 2, &out);
    let output = merge(
        &[folder(0), out.join("other/shard_1_of_2")],
        &dir.join("merged"),
    );
    fails_with(&output, 1, &["is of scene other", "of scene hertz-loads"]);
    // A file a shard listed is gone; a partial result is not one (its line said).
    shard(&scene, 1, 2, &out);
    std::fs::remove_file(folder(0).join("p_map_1.svg")).unwrap();
    let output = merge(&[folder(0), folder(1)], &dir.join("merged"));
    fails_with(&output, 1, &["shard_0_of_2/p_map_1.svg"]);
    std::fs::write(folder(1).join("partial.json"), "{\"shard\": 1}").unwrap();
    let output = merge(&[folder(0), folder(1)], &dir.join("merged"));
    fails_with(
        &output,
        1,
        &["not a partial result of contopt run --shard", "line 1"],
    );
    let output = merge(std::slice::from_ref(&dir), &dir.join("merged"));
    fails_with(&output, 1, &["no partial.json and no shard_K_of_N folders"]);
    assert!(!dir.join("merged").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
