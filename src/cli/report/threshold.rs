//! The threshold commands' reports: `escape` (the escape speed v_e) and `critical` (the
//! critical radius ξ0c), with what each search cost and can vouch for.

use super::*;

/// One run of a threshold's coarse scan.
#[derive(Debug, Serialize)]
pub struct ScanPoint {
    pub v0: f64,
    pub outcome: Outcome,
}

/// `escape --json`: the escape speed v_e(ξ0, φ) and how it was found.
#[derive(Debug, Serialize)]
pub struct EscapeReport {
    pub xi0: f64,
    pub phi: f64,
    pub v_escape: f64,
    pub stuck_at: Option<f64>,
    pub escapes_at: f64,
    pub interval: bool,
    pub scan: Vec<ScanPoint>,
    #[serde(flatten)]
    pub solve: SolveReport,
}

/// `critical --json`: the critical radius ξ0c and, with `--omega --r0c`, μ by Eq. 22.
#[derive(Debug, Serialize)]
pub struct CriticalReport {
    pub xi0c: f64,
    pub stuck_at: Option<f64>,
    pub escapes_at: f64,
    pub interval: bool,
    pub mu: Option<f64>,
    #[serde(flatten)]
    pub solve: SolveReport,
}

/// What a threshold search cost and what it can vouch for.
#[derive(Debug, Serialize)]
pub struct SolveReport {
    /// μ_s/μ_k of the runs (1: the paper's).
    pub mu_static_ratio: f64,
    pub runs: u32,
    pub rhs_evals: u64,
    pub run_tol: Option<f64>,
    /// How many times the search was run again tighter (said in the text only).
    #[serde(skip)]
    pub tightened: u32,
    pub certified: Option<bool>,
}

impl SolveReport {
    pub fn new(t: &Threshold, certified: Option<bool>, settings: &Settings) -> SolveReport {
        SolveReport {
            mu_static_ratio: settings.hold(),
            runs: t.runs,
            rhs_evals: t.rhs_evals,
            run_tol: t.run_tol,
            tightened: t.tightened,
            certified,
        }
    }

    fn text(&self) -> String {
        let at = self
            .run_tol
            .map_or(String::new(), |tol| format!(" (runs at tol {tol:.0e})"));
        let checked = match self.certified {
            None => "",
            Some(true) => {
                "checked  certified: each end run in full ends as it says, and so does a second opinion (dop853, tighter, in the other frame)\n"
            }
            Some(false) => &format!(
                "checked  NOT certified: an end of the bracket, run in full or by its second opinion, did not end as it says with a margin{}\n",
                match self.tightened {
                    0 => String::new(),
                    n => format!(", even solved again with runs 10^{}x tighter", 2 * n),
                }
            ),
        };
        let hold = if self.mu_static_ratio == 1.0 {
            String::new()
        } else {
            format!(
                "static   mu_s/mu_k = {}: a particle at rest holds out to xi = {0}\n",
                self.mu_static_ratio
            )
        };
        format!(
            "{hold}cost     {} runs, {} rhs evaluations{at}\n{checked}",
            self.runs, self.rhs_evals
        )
    }
}

impl EscapeReport {
    pub fn new(
        xi0: f64,
        phi: f64,
        t: &Threshold,
        certified: Option<bool>,
        settings: &Settings,
    ) -> EscapeReport {
        EscapeReport {
            xi0,
            // + 0.0: −0 reads 0.
            phi: turn_angle(phi) + 0.0,
            v_escape: t.value,
            stuck_at: t.stuck_at,
            escapes_at: t.escapes_at,
            interval: t.interval,
            scan: t
                .scan
                .iter()
                .map(|&(v0, e)| ScanPoint {
                    v0,
                    outcome: if e { Outcome::Escaped } else { Outcome::Stuck },
                })
                .collect(),
            solve: SolveReport::new(t, certified, settings),
        }
    }

    /// The scan as runs of equal outcome: "0 to 1.2 escape; 1.35 to 2.4 stick; …" (what is
    /// known where the escaping values are not one interval).
    fn scan_summary(&self) -> String {
        let mut parts: Vec<String> = Vec::new();
        for run in self.scan.chunk_by(|a, b| a.outcome == b.outcome) {
            let (first, last) = (&run[0], &run[run.len() - 1]);
            let range = if run.len() == 1 {
                format!("{:.4}", first.v0)
            } else {
                format!("{:.4} to {:.4}", first.v0, last.v0)
            };
            let word = if first.outcome == Outcome::Escaped {
                "escape"
            } else {
                "stick"
            };
            parts.push(format!("{range} {word}"));
        }
        parts.join("; ")
    }
}

impl Report for EscapeReport {
    fn text(&self) -> String {
        let mut text = match self.stuck_at {
            Some(lo) => format!(
                "v_escape {:.10}  (the least escaping speed)\nbracket  stuck at {lo:.10}, escapes at {:.10}\n",
                self.v_escape, self.escapes_at
            ),
            None => "v_escape 0  (released at rest on the table here, it already escapes)\n".into(),
        };
        text.push_str(&self.solve.text());
        if !self.interval {
            let _ = writeln!(
                text,
                "note     the escaping speeds are not one interval: some faster releases come to rest.\n         scanned v0: {}",
                self.scan_summary()
            );
        }
        text
    }
}

impl CriticalReport {
    pub fn new(
        t: &Threshold,
        certified: Option<bool>,
        mu: Option<f64>,
        settings: &Settings,
    ) -> CriticalReport {
        CriticalReport {
            xi0c: t.value,
            stuck_at: t.stuck_at,
            escapes_at: t.escapes_at,
            interval: t.interval,
            mu,
            solve: SolveReport::new(t, certified, settings),
        }
    }
}

impl Report for CriticalReport {
    fn text(&self) -> String {
        let mut text = format!(
            "xi0c     {:.10}\nbracket  stuck at {:.10}, escapes at {:.10}\n{}",
            self.xi0c,
            self.stuck_at.unwrap_or(0.0),
            self.escapes_at,
            self.solve.text()
        );
        if let Some(mu) = self.mu {
            let _ = writeln!(text, "mu       {mu:.6}  (Eq. 22: Omega² r0c / (xi0c g))");
        }
        text
    }
}
