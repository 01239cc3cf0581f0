//! `turntable bench`: the work–precision table, as text, JSON or braille charts.

use super::{BenchArgs, CmdResult, Error};
use crate::bench::{self, Config, Task};
use crate::files::emit;

pub fn bench(a: BenchArgs) -> CmdResult {
    #[cfg(feature = "serve")]
    if !a.serve.is_empty() {
        return serve(&a);
    }
    let mut cfg = if a.quick {
        Config::quick()
    } else {
        Config::full()
    };
    if let Some(n) = a.cases {
        if n > 10_000 {
            return Err(Error::invalid(format!(
                "--cases must be at most 10000, got {n}"
            )));
        }
        cfg.cases = n;
    }
    if let Some(s) = a.seed {
        cfg.seed = s;
    }
    cfg.python = Some(a.python);
    let bar = super::progress::tasks();
    let report = bench::run(&cfg, |task| bar.set_message(format!("bench: {task}")));
    bar.finish_and_clear();
    let report = report?;
    let mut out = if a.json {
        serde_json::to_string_pretty(&report).map_err(|e| Error::Failed(e.to_string()))? + "\n"
    } else {
        bench::table(&report)
    };
    if a.plot {
        for t in [Task::Rest, Task::Drift, Task::Escape] {
            out.push('\n');
            out.push_str(&bench::plot(&report, t, 72, 20)?);
        }
    }
    emit(None, &out)?;
    Ok(())
}

/// `--serve N,...`: one row per client count, printed as it is measured.
#[cfg(feature = "serve")]
fn serve(a: &BenchArgs) -> CmdResult {
    if !(1.0..=3600.0).contains(&a.seconds) || a.serve.iter().any(|&n| !(1..=1000).contains(&n)) {
        return Err(Error::invalid(
            "--serve takes 1 to 1000 clients a row, --seconds 1 to 3600",
        ));
    }
    for &n in &a.serve {
        if a.followers {
            followers(a, n)?;
            continue;
        }
        let bar = super::progress::tasks();
        bar.set_message(format!("bench: serve with {n} clients for {} s", a.seconds));
        let row = bench::serve::run(n, a.seconds);
        bar.finish_and_clear();
        let row = row?;
        let line = if a.json {
            serde_json::to_string(&row).map_err(|e| Error::Failed(e.to_string()))?
        } else {
            bench::serve::line(&row)
        };
        emit(None, &(line + "\n"))?;
        if a.attacks {
            attacks(a, n)?;
        }
    }
    Ok(())
}

/// `--followers`: a presenter and `n` students following it.
#[cfg(feature = "serve")]
fn followers(a: &BenchArgs, n: usize) -> CmdResult {
    let bar = super::progress::tasks();
    bar.set_message(format!(
        "bench: a presenter and {n} followers for {} s",
        a.seconds
    ));
    let row = bench::follow::run(n, a.seconds);
    bar.finish_and_clear();
    let row = row?;
    let line = if a.json {
        serde_json::to_string(&row).map_err(|e| Error::Failed(e.to_string()))?
    } else {
        bench::follow::line(&row)
    };
    emit(None, &(line + "\n"))?;
    Ok(())
}

/// `--attacks`: the rows of one client's floods beside a class of `n` students.
#[cfg(feature = "serve")]
fn attacks(a: &BenchArgs, n: usize) -> CmdResult {
    let bar = super::progress::tasks();
    bar.set_message(format!(
        "bench: attacks beside {n} students, {} s each",
        a.seconds
    ));
    let rows = bench::attacks::run(n, a.seconds);
    bar.finish_and_clear();
    for row in rows? {
        let line = if a.json {
            serde_json::to_string(&row).map_err(|e| Error::Failed(e.to_string()))?
        } else {
            bench::attacks::line(&row)
        };
        emit(None, &(line + "\n"))?;
    }
    Ok(())
}
