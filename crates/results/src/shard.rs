//! Job arrays: a scene's cases split into `N` shards, each run on its own (`contopt run
//! --shard K/N`, one task of a Slurm job array) into a [`Partial`] result, and the partial
//! results joined into the [`Report`] one run of the whole scene gives ([`merge`]).
//!
//! Shard `K` of `N` runs a contiguous block of the scene's cases ([`Shard::cases`]): cases
//! next to each other usually share their bodies (a sweep over the load or the controller),
//! which a run builds once, so blocks build fewer bodies than cases dealt round-robin. The
//! split depends on the case count and `N` only, so every task computes the same one.

use std::ops::Range;

use serde::{Deserialize, Serialize};

use crate::{Report, SCHEMA_VERSION};

/// Shard `index` of `count` (`K/N`, `K` counted from 0 as Slurm's `--array=0-(N-1)` numbers
/// its tasks).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shard {
    /// K, from 0.
    pub index: usize,
    /// N, at least 1.
    pub count: usize,
}

/// Why a shard or a set of partial results is refused.
#[derive(Debug, thiserror::Error)]
pub enum ShardError {
    /// `--shard` is not `K/N` with 0 ≤ K < N.
    #[error("--shard {given:?}: {reason}")]
    Spec {
        /// The text given.
        given: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The partial results do not make one run of one scene.
    #[error("{0}")]
    Mismatch(String),
}

impl Shard {
    /// Reads `K/N` (`3/8`): whole numbers, N ≥ 1, K < N.
    pub fn parse(text: &str) -> Result<Self, ShardError> {
        let spec = |reason: &str| ShardError::Spec {
            given: text.to_string(),
            reason: reason.to_string(),
        };
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| spec("write the shard as K/N, e.g. 0/4 for the first of four"))?;
        let whole = |s: &str, what: &str| {
            s.trim().parse::<usize>().map_err(|_| {
                spec(&format!(
                    "{what} {s:?} is not a whole number ≥ 0 (write K/N, e.g. 0/4)"
                ))
            })
        };
        let (index, count) = (whole(k, "K")?, whole(n, "N")?);
        if count == 0 {
            return Err(spec("N = 0: a scene is split into at least one shard"));
        }
        if index >= count {
            return Err(spec(&format!(
                "K = {index} is not below N = {count}: shards are numbered 0 to {}",
                count - 1
            )));
        }
        Ok(Self { index, count })
    }

    /// The cases of this shard among `total`: the `index`-th of `count` contiguous blocks whose
    /// sizes differ by at most one (empty when there are fewer cases than shards).
    pub fn cases(&self, total: usize) -> Range<usize> {
        let start = |k: usize| k * total / self.count;
        start(self.index)..start(self.index + 1)
    }

    /// The name of the shard's results folder, `shard_K_of_N`.
    pub fn folder(&self) -> String {
        format!("shard_{}_of_{}", self.index, self.count)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The result of one shard (`partial.json`): its cases' reports, and what [`merge`] checks
/// to join it with the others — the scene, its version, the split.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Partial {
    /// The version of contopt that ran it: shards of one result run one version.
    pub contopt_version: String,
    /// Which shard.
    pub shard: Shard,
    /// The scene's case count.
    pub scene_cases: usize,
    /// A fingerprint of the scene's resolved cases (their labels and inputs): shards of a
    /// changed scene do not join.
    pub fingerprint: String,
    /// The shard's cases, in the scene's order (`schema_version`, scene and description as
    /// the whole run's).
    pub report: Report,
}

/// A partial result and where it was read from (for messages).
pub type Located = (String, Partial);

/// The report one run of the scene gives, from the partial results of all its shards, given
/// in any order: refused, naming the values, when they are of different scenes, versions of a
/// scene or of contopt, or splits, when a shard is given twice or missing, or when a shard
/// holds other cases than its own.
pub fn merge(mut parts: Vec<Located>) -> Result<Report, ShardError> {
    let Some((_, first)) = parts.first() else {
        return Err(ShardError::Mismatch("no partial results to merge".into()));
    };
    let (count, scene) = (first.shard.count, first.report.scene.clone());
    for (file, p) in &parts {
        alike(file, p, &parts[0])?;
    }
    parts.sort_by_key(|(_, p)| p.shard.index);
    for pair in parts.windows(2) {
        if pair[0].1.shard == pair[1].1.shard {
            return Err(ShardError::Mismatch(format!(
                "shard {} is given twice: {} and {}",
                pair[0].1.shard, pair[0].0, pair[1].0
            )));
        }
    }
    let missing: Vec<String> = (0..count)
        .filter(|k| !parts.iter().any(|(_, p)| p.shard.index == *k))
        .map(|k| format!("{k}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(ShardError::Mismatch(format!(
            "shard {} of scene {scene} missing: run it (contopt run … --shard K/N) and merge \
             again",
            missing.join(", ")
        )));
    }
    let description = parts[0].1.report.description.clone();
    Ok(Report {
        schema_version: SCHEMA_VERSION,
        scene,
        description,
        cases: parts
            .into_iter()
            .flat_map(|(_, p)| p.report.cases)
            .collect(),
    })
}

/// Refuses the partial result `p`, read from `file`, unless it is of the run `first` is of
/// and holds its own share of the cases.
fn alike(file: &str, p: &Partial, (first_file, first): &Located) -> Result<(), ShardError> {
    let mismatch = |m: String| Err(ShardError::Mismatch(m));
    let differs = |what: &str, a: &dyn std::fmt::Display, b: &dyn std::fmt::Display| {
        mismatch(format!(
            "{file} is {what} {a}, {first_file} {what} {b}: merge the shards of one run"
        ))
    };
    if p.report.schema_version != SCHEMA_VERSION {
        return mismatch(format!(
            "{file} has result schema {}, this contopt writes {SCHEMA_VERSION}: merge with the \
             contopt that ran the shards",
            p.report.schema_version
        ));
    }
    if p.report.scene != first.report.scene {
        return differs("of scene", &p.report.scene, &first.report.scene);
    }
    if p.fingerprint != first.fingerprint || p.scene_cases != first.scene_cases {
        return mismatch(format!(
            "{file} and {first_file} are of different versions of scene {} (fingerprints {} and \
             {}, {} and {} cases): run every shard from the same scene file",
            p.report.scene, p.fingerprint, first.fingerprint, p.scene_cases, first.scene_cases
        ));
    }
    if p.contopt_version != first.contopt_version {
        return differs("from contopt", &p.contopt_version, &first.contopt_version);
    }
    if p.shard.count != first.shard.count {
        return differs("a shard of", &p.shard.count, &first.shard.count);
    }
    let own = p.shard.cases(p.scene_cases);
    if p.report.cases.len() != own.len() {
        return mismatch(format!(
            "{file} (shard {}) holds {} cases, its share is {} (cases {} to {})",
            p.shard,
            p.report.cases.len(),
            own.len(),
            own.start + 1,
            own.end
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every case falls in exactly one shard, in order, the shards' sizes within one.
    #[test]
    fn shards_split_the_cases_in_order() {
        for total in 0..20 {
            for count in 1..8 {
                let ranges: Vec<_> = (0..count)
                    .map(|index| Shard { index, count }.cases(total))
                    .collect();
                assert_eq!(ranges[0].start, 0);
                assert_eq!(ranges[count - 1].end, total);
                for w in ranges.windows(2) {
                    assert_eq!(w[0].end, w[1].start);
                }
                let sizes: Vec<usize> = ranges.iter().map(|r| r.len()).collect();
                let (lo, hi) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
                assert!(hi - lo <= 1, "{total} cases, {count} shards: {sizes:?}");
            }
        }
    }

    /// Bad shards are refused naming the value.
    #[test]
    fn bad_shards_are_refused() {
        assert_eq!(Shard::parse("2/4").unwrap(), Shard { index: 2, count: 4 });
        for (given, says) in [
            ("4/4", "K = 4 is not below N = 4"),
            ("0/0", "N = 0"),
            ("1", "write the shard as K/N"),
            ("-1/4", "K \"-1\" is not a whole number"),
            ("1/x", "N \"x\" is not a whole number"),
        ] {
            let message = Shard::parse(given).unwrap_err().to_string();
            assert!(message.contains(says), "{given}: {message}");
            assert!(message.contains(&format!("{given:?}")), "{message}");
        }
    }

    fn partial(index: usize, count: usize, scene: &str, fingerprint: &str) -> Located {
        let shard = Shard { index, count };
        let cases = shard
            .cases(5)
            .map(|k| crate::CaseReport::new(&format!("case {k}"), &Default::default(), 0.into()))
            .collect();
        let report = Report {
            schema_version: SCHEMA_VERSION,
            scene: scene.into(),
            description: String::new(),
            cases,
        };
        let p = Partial {
            contopt_version: "1".into(),
            shard,
            scene_cases: 5,
            fingerprint: fingerprint.into(),
            report,
        };
        (format!("s{index}"), p)
    }

    /// Shards given in any order join in the scene's order; a missing, doubled, foreign or
    /// changed shard is refused, naming it.
    #[test]
    fn merge_checks_the_shards() {
        let all = |scene1: &str, fp2: &str| {
            vec![
                partial(2, 3, "a", fp2),
                partial(0, 3, "a", "f"),
                partial(1, 3, scene1, "f"),
            ]
        };
        let report = merge(all("a", "f")).unwrap();
        let labels: Vec<_> = report.cases.iter().map(|c| c.label.as_str()).collect();
        assert_eq!(labels, ["case 0", "case 1", "case 2", "case 3", "case 4"]);
        let refused = |parts: Vec<Located>, says: &str| {
            let message = merge(parts).unwrap_err().to_string();
            assert!(message.contains(says), "{message}");
        };
        refused(all("b", "f"), "s1 is of scene b, s2 of scene a");
        refused(
            all("a", "g"),
            "s0 and s2 are of different versions of scene a (fingerprints f and g",
        );
        let mut parts = all("a", "f");
        parts.pop();
        refused(parts, "shard 1/3 of scene a missing");
        let mut parts = all("a", "f");
        parts.push(partial(1, 3, "a", "f"));
        refused(parts, "shard 1/3 is given twice");
        let mut parts = all("a", "f");
        parts.push(partial(1, 4, "a", "f"));
        refused(parts, "s1 is a shard of 4, s2 a shard of 3");
        let mut parts = all("a", "f");
        parts[0].1.report.cases.pop();
        refused(parts, "s2 (shard 2/3) holds 1 cases, its share is 2");
    }
}
