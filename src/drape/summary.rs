//! The batch's summary: one entry per pattern, read back from the report its run wrote,
//! as JSON (`summary.json`) and as a table (`summary.md`).

use crate::scene_file::{median, CLEAN, CLEAN_P99_STRAIN, REASONS, STRETCHED};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::fmt::Write as _;
use std::path::Path;

pub const SUMMARY_JSON: &str = "summary.json";
pub const SUMMARY_MD: &str = "summary.md";

/// How one pattern's drape ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SummaryEntry {
    pub name: String,
    /// The pattern file.
    pub pattern: String,
    /// "finished" (sewn and draped to rest or to the step limit), "failed" (refused, or
    /// the run failed), or "interrupted".
    pub outcome: String,
    /// Finished by an earlier batch and not run again.
    pub skipped: bool,
    /// Why it failed or stopped.
    pub failure: Option<String>,
    /// A finished garment's verdict: "clean", or why not, naming the panels (see
    /// [`crate::scene_file::RunReport::verdict`]).
    pub verdict: Option<String>,
    /// Wall time of its run, s.
    pub seconds: f64,
    pub particles: Option<usize>,
    pub sewing_steps: Option<u64>,
    pub draping_steps: Option<u64>,
    /// How the drape stage ended: "at_rest", "step_limit", ...
    pub drape_ended: Option<String>,
    pub self_intersections: Option<usize>,
    pub body_intersections: Option<usize>,
    /// Crossings of the body's thin parts by panels passing them for the whole run.
    pub thin_parts_passed: Option<usize>,
    /// m.
    pub deepest_penetration: Option<f64>,
    /// %.
    pub max_warp: Option<f64>,
    pub max_weft: Option<f64>,
    pub p99_warp: Option<f64>,
    pub p99_weft: Option<f64>,
    /// What a finished garment's cut asks of the fabric round the body where it is most
    /// stretched, % (negative: the slack it leaves there); none where the fit was not
    /// measured (see [`crate::scene_file::Fit`]).
    pub fit_asks: Option<f64>,
}

impl SummaryEntry {
    /// A pattern refused before it ran (nothing in its folder but, maybe, its scene).
    pub fn refused(name: &str, pattern: &Path, reason: String, seconds: f64) -> Self {
        Self {
            name: name.to_string(),
            pattern: pattern.display().to_string(),
            outcome: "failed".into(),
            skipped: false,
            failure: Some(reason),
            verdict: None,
            seconds,
            particles: None,
            sewing_steps: None,
            draping_steps: None,
            drape_ended: None,
            self_intersections: None,
            body_intersections: None,
            thin_parts_passed: None,
            deepest_penetration: None,
            max_warp: None,
            max_weft: None,
            p99_warp: None,
            p99_weft: None,
            fit_asks: None,
        }
    }

    /// The entry of a run whose report is `folder/report.json`; `None` when it has none
    /// or it cannot be read.
    pub fn from_report(name: &str, pattern: &Path, folder: &Path, skipped: bool) -> Option<Self> {
        let text = std::fs::read_to_string(folder.join("report.json")).ok()?;
        let r: Value = serde_json::from_str(&text).ok()?;
        let outcome = r["outcome"]["kind"].as_str()?.to_string();
        let failure = match outcome.as_str() {
            "failed" => r["outcome"]["error"].as_str().map(str::to_string),
            "interrupted" => Some(format!(
                "interrupted at {} step {}",
                r["outcome"]["stage"].as_str().unwrap_or("?"),
                r["outcome"]["step"]
            )),
            _ => None,
        };
        let stage = |name: &str| {
            r["stages"]
                .as_array()
                .and_then(|stages| stages.iter().find(|s| s["stage"] == name))
        };
        let steps = |name: &str| stage(name).and_then(|s| s["steps"].as_u64());
        let count = |key: &str| r[key].as_u64().map(|n| n as usize);
        Some(Self {
            name: name.to_string(),
            pattern: pattern.display().to_string(),
            outcome,
            skipped,
            failure,
            verdict: r["verdict"].as_str().map(str::to_string),
            seconds: r["total_seconds"].as_f64().unwrap_or(0.0),
            particles: count("particles"),
            sewing_steps: steps("sewing"),
            draping_steps: steps("draping"),
            drape_ended: stage("draping").and_then(|s| s["ended"].as_str().map(str::to_string)),
            self_intersections: count("self_intersections"),
            body_intersections: count("body_intersections"),
            thin_parts_passed: count("thin_parts_passed"),
            deepest_penetration: r["deepest_penetration"].as_f64(),
            max_warp: r["strain"]["max_warp"].as_f64(),
            max_weft: r["strain"]["max_weft"].as_f64(),
            p99_warp: r["strain"]["p99_warp"].as_f64(),
            p99_weft: r["strain"]["p99_weft"].as_f64(),
            fit_asks: r["fit"]["asks"].as_f64(),
        })
    }

    pub fn finished(&self) -> bool {
        self.outcome == "finished"
    }

    /// This run, interrupted by a time limit of `limit` s rather than by the user, as a
    /// failure that says so.
    pub fn stopped_by_time_limit(&mut self, limit: f64) {
        self.outcome = "failed".into();
        self.failure = Some(format!(
            "{TIME_LIMIT} of {limit} s ({})",
            self.failure.as_deref().unwrap_or("")
        ));
    }

    fn timed_out(&self) -> bool {
        self.failure.as_deref().is_some_and(|f| f.starts_with(TIME_LIMIT))
    }
}

/// What a run stopped by the batch's time limit says first.
const TIME_LIMIT: &str = "stopped by the time limit";

/// Writes `summary.json` and `summary.md` into `dir` (each whole, then renamed into
/// place, so a batch killed while writing leaves the last complete one).
pub fn write_summary(dir: &Path, entries: &[SummaryEntry]) -> std::io::Result<()> {
    let json = serde_json::to_string_pretty(entries).expect("entries serialise");
    cloth_formats::atomic::write_atomically(&dir.join(SUMMARY_JSON), |w| w.write_all(json.as_bytes()))?;
    let table = markdown(entries);
    cloth_formats::atomic::write_atomically(&dir.join(SUMMARY_MD), |w| w.write_all(table.as_bytes()))
}

fn markdown(entries: &[SummaryEntry]) -> String {
    let finished = entries.iter().filter(|e| e.finished()).count();
    let clean = entries
        .iter()
        .filter(|e| e.verdict.as_deref() == Some(CLEAN))
        .count();
    let mut out = format!(
        "# Drape summary\n\n{finished} of {} patterns finished, {clean} of them clean (at rest, nothing \
         through itself or the body, p99 warp and weft strain under {CLEAN_P99_STRAIN} %).\n\n",
        entries.len()
    );
    out += &tally(entries);
    out += "| pattern | outcome | seconds | particles | sewing steps | draping steps | self / body intersections | deepest penetration, mm | max warp / weft, % | p99 warp / weft, % | verdict, or why it failed |\n";
    out += "|---|---|---|---|---|---|---|---|---|---|---|\n";
    let num = |v: Option<f64>, digits: usize| v.map_or("-".to_string(), |x| format!("{x:.digits$}"));
    let int = |v: Option<u64>| v.map_or("-".to_string(), |x| x.to_string());
    for e in entries {
        let outcome = if e.skipped {
            format!("{} (earlier)", e.outcome)
        } else {
            e.outcome.clone()
        };
        let ended = e
            .drape_ended
            .as_deref()
            .map_or(String::new(), |d| format!(" ({d})"));
        let _ = writeln!(
            out,
            "| {} | {}{} | {:.1} | {} | {} | {} | {} / {} | {} | {} / {} | {} / {} | {} |",
            e.name,
            outcome,
            ended,
            e.seconds,
            int(e.particles.map(|n| n as u64)),
            int(e.sewing_steps),
            int(e.draping_steps),
            int(e.self_intersections.map(|n| n as u64)),
            int(e.body_intersections.map(|n| n as u64)),
            num(e.deepest_penetration.map(|d| 1e3 * d), 1),
            num(e.max_warp, 2),
            num(e.max_weft, 2),
            num(e.p99_warp, 2),
            num(e.p99_weft, 2),
            e.failure
                .as_deref()
                .or(e.verdict.as_deref())
                .unwrap_or("")
                .replace('|', "/")
                .replace('\n', " "),
        );
    }
    out
}

/// The lines under the count: how many garments each reason left unclean, how many
/// failed, and the time a pattern took in this batch (those finished by an earlier batch
/// left out), so that a corpus run reads as one line of figures.
fn tally(entries: &[SummaryEntry]) -> String {
    let mut out = String::new();
    // Only a finished garment has a verdict; its reasons are joined by "; ", each
    // beginning with its kind.
    let unclean: Vec<&str> = entries
        .iter()
        .filter_map(|e| e.verdict.as_deref())
        .filter(|&v| v != CLEAN)
        .collect();
    if !unclean.is_empty() {
        let counts: Vec<String> = REASONS
            .iter()
            .map(|reason| {
                let n = unclean
                    .iter()
                    .filter(|v| v.split("; ").any(|r| r.starts_with(reason)))
                    .count();
                format!("{reason} {n}")
            })
            .collect();
        let _ = writeln!(
            out,
            "Finished but not clean: {} ({}; a garment may have more than one reason).\n",
            unclean.len(),
            counts.join(", ")
        );
    }
    // Stretched and nothing else, where the cut is smaller than the body: the design asks
    // that stretch of the fabric on this body, whatever the drape does.
    let cut_small: Vec<f64> = entries
        .iter()
        .filter(|e| {
            e.verdict
                .as_deref()
                .is_some_and(|v| v.split("; ").all(|r| r.starts_with(STRETCHED)))
        })
        .filter_map(|e| e.fit_asks.filter(|&asks| asks > 0.0))
        .collect();
    if !cut_small.is_empty() {
        let least = cut_small.iter().copied().fold(f64::INFINITY, f64::min);
        let most = cut_small.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let _ = writeln!(
            out,
            "Stretched only, each cut smaller than the body where it is most stretched: {} (the cut asks {least:.1} to {most:.1} % round the body there).\n",
            cut_small.len()
        );
    }
    let failed = entries.iter().filter(|e| e.outcome == "failed").count();
    if failed > 0 {
        let timed_out = entries.iter().filter(|e| e.timed_out()).count();
        let _ = writeln!(out, "Failed: {failed} ({timed_out} of them {TIME_LIMIT}).\n");
    }
    let run: Vec<&SummaryEntry> = entries.iter().filter(|e| !e.skipped).collect();
    if let Some(slowest) = run.iter().max_by(|a, b| a.seconds.total_cmp(&b.seconds)) {
        let seconds: Vec<f64> = run.iter().map(|e| e.seconds).collect();
        let _ = writeln!(
            out,
            "Time per pattern, over the {} run in this batch: median {:.1} s, slowest {:.1} s ({}).\n",
            run.len(),
            median(&seconds),
            slowest.seconds,
            slowest.name
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(name: &str, seconds: f64, verdict: Option<&str>) -> SummaryEntry {
        let mut e = SummaryEntry::refused(name, Path::new("p.json"), "refused".into(), seconds);
        if let Some(v) = verdict {
            e.outcome = "finished".into();
            e.failure = None;
            e.verdict = Some(v.into());
        }
        e
    }

    #[test]
    fn the_summary_counts_each_reason_and_failure_and_times_the_patterns_run() {
        let mut timed_out = entry("slow", 600.4, None);
        timed_out.outcome = "interrupted".into();
        timed_out.failure = Some("interrupted at draping step 90".into());
        timed_out.stopped_by_time_limit(600.0);
        let mut earlier = entry("earlier", 900.0, Some(CLEAN));
        earlier.skipped = true;
        let entries = [
            entry("a", 10.0, Some(CLEAN)),
            entry("b", 20.0, Some("stretched: p99 weft strain 8.0 %, over 5 %")),
            entry(
                "c",
                40.0,
                Some("through itself: 2 edge-triangle pairs; stretched: p99 weft strain 6.1 %, over 5 %"),
            ),
            entry("d", 5.0, None),
            timed_out,
            earlier,
        ];
        let table = markdown(&entries);
        assert!(
            table.contains("4 of 6 patterns finished, 2 of them clean"),
            "{table}"
        );
        assert!(
            table.contains(
                "Finished but not clean: 2 (not at rest 0, through itself 1, through the body 0, stretched 2;"
            ),
            "{table}"
        );
        assert!(
            table.contains("Failed: 2 (1 of them stopped by the time limit)."),
            "{table}"
        );
        assert!(
            entries[4].failure.as_deref().is_some_and(
                |f| f.starts_with("stopped by the time limit of 600 s (interrupted at draping step 90)")
            ),
            "{:?}",
            entries[4].failure
        );
        // The one finished by an earlier batch is not timed: the median of 5, 10, 20, 40 and
        // 600.4.
        assert!(
            table.contains("over the 5 run in this batch: median 20.0 s, slowest 600.4 s (slow)."),
            "{table}"
        );
    }

    #[test]
    fn a_batch_all_clean_says_no_reasons_and_an_even_count_takes_the_middle_two() {
        let table = markdown(&[entry("a", 10.0, Some(CLEAN)), entry("b", 30.0, Some(CLEAN))]);
        assert!(
            !table.contains("not clean") && !table.contains("Failed"),
            "{table}"
        );
        assert!(table.contains("median 20.0 s, slowest 30.0 s (b)"), "{table}");
        assert!(!table.contains("Stretched only"), "{table}");
    }

    #[test]
    fn garments_stretched_only_where_cut_smaller_than_the_body_are_counted_with_what_the_cut_asks() {
        let stretched = |name: &str, verdict: &str, asks: Option<f64>| {
            let mut e = entry(name, 1.0, Some(verdict));
            e.fit_asks = asks;
            e
        };
        let only = "stretched: p99 weft strain 8.0 %, over 5 %";
        let entries = [
            stretched("small", only, Some(8.0)),
            stretched("a little small", only, Some(4.2)),
            // Stretched with room to spare, or unmeasured: not the cut's doing, or not known.
            stretched("roomy", only, Some(-3.0)),
            stretched("unmeasured", only, None),
            // Through itself too: not stretched only.
            stretched(
                "tangled",
                &format!("through itself: 2 edge-triangle pairs; {only}"),
                Some(6.0),
            ),
            stretched("clean", CLEAN, Some(1.0)),
        ];
        let table = markdown(&entries);
        assert!(
            table.contains(
                "Stretched only, each cut smaller than the body where it is most stretched: 2 (the cut asks 4.2 to 8.0 % round the body there)."
            ),
            "{table}"
        );
    }
}
