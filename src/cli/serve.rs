//! `turntable serve`: the explorer over SSH for a class (see `crate::serve`). Prints where it
//! listens, the host key's fingerprint and the passphrases; runs until SIGTERM or SIGINT,
//! which close every session with a message, and exits 0.

use super::{CmdResult, Error};
use crate::script::parse_size;
use crate::serve::{Limits, Options};
use clap::Args;
use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

#[derive(Args, Debug)]
pub struct ServeArgs {
    /// Address and port to listen on. Another address than the loopback is your choice to
    /// make: every machine that reaches it may try to get in.
    #[arg(long, value_name = "ADDR:PORT", default_value = "127.0.0.1:2222")]
    pub listen: std::net::SocketAddr,
    /// Public keys (OpenSSH authorized_keys format) that get in as students. Their from="…"
    /// and expiry-time="…Z" options are honoured, restrict and no-… taken, any other refused.
    #[arg(long, value_name = "FILE")]
    pub authorized_keys: Option<PathBuf>,
    /// The class's passphrase (typed at ssh's password prompt, any user name). Without it or
    /// --authorized-keys, one is made and printed.
    #[arg(long, value_name = "WORDS")]
    pub passphrase: Option<String>,
    /// Public keys that get in as the presenter, whom every follower's explorer follows.
    #[arg(long, value_name = "FILE")]
    pub presenter_keys: Option<PathBuf>,
    /// The presenter's passphrase. Without it or --presenter-keys, one is made and printed.
    #[arg(long, value_name = "WORDS")]
    pub presenter_passphrase: Option<String>,
    /// The host key (made there, 0600, if missing). Default:
    /// $XDG_DATA_HOME/turntable/ssh_host_ed25519_key.
    #[arg(long, value_name = "FILE")]
    pub host_key: Option<PathBuf>,
    /// Explorers open at once (the presenter has places beyond them).
    #[arg(long, default_value_t = Limits::default().sessions, value_name = "N", value_parser = at_least_1())]
    pub max_sessions: usize,
    /// New connections from one address in a minute.
    #[arg(long, default_value_t = Limits::default().per_minute, value_name = "N", value_parser = at_least_1())]
    pub per_minute: usize,
    /// Connections not yet logged in, in all (past it, the oldest of the address holding the
    /// most makes room for a newcomer). Default: 100, or --max-sessions + 16 if larger.
    #[arg(long, value_name = "N", value_parser = at_least_1())]
    pub max_waiting: Option<usize>,
    /// Connections not yet logged in from one address. Default: --max-sessions + 16 (a class
    /// behind one address connects at once); lower it when students have addresses of their own.
    #[arg(long, value_name = "N", value_parser = at_least_1())]
    pub max_waiting_per_address: Option<usize>,
    /// Seconds a connection has to log in.
    #[arg(long, default_value_t = Limits::default().handshake.as_secs(), value_name = "SECONDS", value_parser = clap::value_parser!(u64).range(1..))]
    pub login_grace: u64,
    /// Seconds a connection logged in has to open the explorer (and stays after it ended).
    #[arg(long, default_value_t = Limits::default().shell_grace.as_secs(), value_name = "SECONDS", value_parser = clap::value_parser!(u64).range(1..))]
    pub shell_grace: u64,
    /// Seconds without a key before a session is closed.
    #[arg(long, default_value_t = Limits::default().idle.as_secs(), value_name = "SECONDS", value_parser = clap::value_parser!(u64).range(1..))]
    pub idle: u64,
    /// The largest terminal drawn, WxH (a larger window is drawn at this size).
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "400x150")]
    pub max_size: (u16, u16),
    /// A lesson (see `turntable lesson --list`) or a lesson file of your own that the
    /// presenter's session runs from its start: every follower takes it in step, and the
    /// presenter sees the class's answers to its questions.
    #[arg(long, value_name = "NAME|PATH")]
    pub lesson: Option<String>,
    /// A directory where the presenter's `E` writes the page as SVG (never over a file; at
    /// most 200 pages and 256 MB there). Without it nothing is written on the server; a
    /// student's `E` never writes.
    #[arg(long, value_name = "DIR")]
    pub exports: Option<PathBuf>,
}

/// A count of 1 or more (0 would serve nobody).
fn at_least_1() -> clap::builder::RangedU64ValueParser<usize> {
    clap::builder::RangedU64ValueParser::new().range(1..)
}

impl ServeArgs {
    /// What no class can run on, refused before anything is read or made.
    fn check(&self) -> Result<(), Error> {
        let (w, h) = self.max_size;
        if w == 0 || h == 0 {
            return Err(Error::invalid(format!(
                "--max-size {w}x{h}: a side of 0 draws nothing (1x1 at least)"
            )));
        }
        for (flag, p) in [
            ("--passphrase", &self.passphrase),
            ("--presenter-passphrase", &self.presenter_passphrase),
        ] {
            if p.as_deref().is_some_and(|p| p.trim().is_empty()) {
                return Err(Error::invalid(format!(
                    "{flag} is empty: nobody could get in with it"
                )));
            }
        }
        if self.passphrase.is_some() && self.passphrase == self.presenter_passphrase {
            return Err(Error::invalid(
                "--passphrase and --presenter-passphrase are the same: every student would \
                 present",
            ));
        }
        Ok(())
    }

    /// The options, with the keys and passphrases read or made; and what to print.
    fn options(&self) -> Result<(Options, Vec<String>), Error> {
        self.check()?;
        let path = match &self.host_key {
            Some(p) => p.clone(),
            None => crate::serve::host_key_path(|v| std::env::var_os(v)).ok_or_else(|| {
                Error::invalid("no XDG_DATA_HOME or HOME for the host key: pass --host-key")
            })?,
        };
        let host_key = crate::serve::host_key(&path)?;
        let read = |f: &Option<PathBuf>| f.as_deref().map(crate::serve::authorized_keys);
        let keys = read(&self.authorized_keys).transpose()?.unwrap_or_default();
        let presenter_keys = read(&self.presenter_keys).transpose()?.unwrap_or_default();
        let mut said = vec![format!(
            "host key {} ({})",
            crate::serve::fingerprint(&host_key),
            crate::files::escape_controls(&path.display().to_string())
        )];
        let passphrase = match (&self.passphrase, &self.authorized_keys) {
            (Some(p), _) => Some(p.clone()),
            (None, Some(_)) => None,
            (None, None) => Some(crate::serve::passphrase()?),
        };
        if let Some(p) = passphrase.as_ref().filter(|_| self.passphrase.is_none()) {
            said.push(format!("class passphrase: {p}"));
        }
        let presenter_passphrase = match (&self.presenter_passphrase, &self.presenter_keys) {
            (Some(p), _) => Some(p.clone()),
            (None, Some(_)) => None,
            (None, None) => Some(crate::serve::passphrase()?),
        };
        if let Some(p) = presenter_passphrase
            .as_ref()
            .filter(|_| self.presenter_passphrase.is_none())
        {
            said.push(format!("presenter passphrase (yours alone): {p}"));
        }
        let limits = Limits {
            sessions: self.max_sessions,
            per_minute: self.per_minute,
            waiting: self.max_waiting,
            waiting_per_address: self.max_waiting_per_address,
            handshake: Duration::from_secs(self.login_grace),
            shell_grace: Duration::from_secs(self.shell_grace),
            idle: Duration::from_secs(self.idle),
            max_cols: self.max_size.0,
            max_rows: self.max_size.1,
            ..Limits::default()
        };
        let lesson = self
            .lesson
            .as_deref()
            .map(super::lesson::for_class)
            .transpose()?;
        if let Some(l) = &lesson {
            said.push(format!("lesson for the class: {}", l.driver.name()));
        }
        if let Some(dir) = &self.exports {
            let shown = crate::files::escape_controls(&dir.display().to_string());
            if !std::fs::metadata(dir).is_ok_and(|m| m.is_dir()) {
                return Err(Error::invalid(format!(
                    "--exports {shown}: not a directory (make it first)"
                )));
            }
            said.push(format!("the presenter's E writes to {shown}"));
        }
        let options = Options {
            lesson,
            listen: self.listen,
            host_key,
            keys,
            passphrase,
            presenter_keys,
            presenter_passphrase,
            limits,
            exports: self.exports.clone(),
        };
        Ok((options, said))
    }
}

pub fn run(a: &ServeArgs) -> CmdResult {
    let (options, said) = a.options()?;
    let mut signals = signal_hook::iterator::Signals::new([
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGINT,
    ])?;
    let running = crate::serve::start(options).map_err(|e| Error::Io {
        what: format!("listening on {}", a.listen),
        source: std::sync::Arc::new(e),
    })?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "turntable serve: listening on {}", running.addr)?;
    for line in said {
        writeln!(out, "{line}")?;
    }
    out.write_all(banner(running.addr, &hosts(running.addr)).as_bytes())?;
    out.flush()?;
    drop(out);
    if let Some(n) = signals.forever().next() {
        running.stop("the server is shutting down");
        let _ = writeln!(std::io::stderr(), "turntable serve: ended by signal {n}");
    }
    Ok(())
}

/// The names a class may reach the server by: the address it listens on, or, listening on
/// every address (`0.0.0.0`, `::`), this machine's address on its default route (a UDP socket
/// connected, which sends nothing) and its host name. None when it has neither.
pub fn hosts(listen: std::net::SocketAddr) -> Vec<String> {
    use std::net::{IpAddr, UdpSocket};
    let ip = listen.ip();
    if !ip.is_unspecified() {
        return vec![ip.to_string()];
    }
    // A public address of the listening family: only its route is looked up.
    let (any, far) = match ip {
        IpAddr::V4(_) => ("0.0.0.0:0", "8.8.8.8:53"),
        IpAddr::V6(_) => ("[::]:0", "[2001:4860:4860::8888]:53"),
    };
    let mut out: Vec<String> = UdpSocket::bind(any)
        .and_then(|s| s.connect(far).and_then(|()| s.local_addr()))
        .map(|a| a.ip())
        .ok()
        .filter(|a| !a.is_loopback() && !a.is_unspecified())
        .map(|a| a.to_string())
        .into_iter()
        .collect();
    let name = rustix::system::uname()
        .nodename()
        .to_string_lossy()
        .into_owned();
    let name = crate::files::escape_controls(&name);
    if !name.is_empty() && name != "localhost" && !name.contains(char::is_whitespace) {
        out.push(name);
    }
    out
}

/// What the teacher is told: where the class reaches the server, and the command each kind of
/// user types there (the first of `hosts`, else `HOST`).
pub fn banner(addr: std::net::SocketAddr, hosts: &[String]) -> String {
    let port = addr.port();
    let host = hosts.first().map_or("HOST", String::as_str);
    let reach = match hosts {
        [] => "HOST: this machine's address on the class's network (none found here)".to_string(),
        [_] if !addr.ip().is_unspecified() => String::new(),
        _ => format!(
            "this machine: {} (the class's network must reach the one you give)",
            hosts.join(", ")
        ),
    };
    let mut s = String::new();
    if !reach.is_empty() {
        s += &format!("{reach}\n");
    }
    s += &format!(
        "students: ssh -p {port} class@{host}   (F2 steps out of the class and back in)\n"
    );
    s += &format!(
        "presenter: ssh -p {port} class@{host}   with the presenter passphrase (or a --presenter-keys key): leads the class\n"
    );
    s += &format!("with a screen reader: ssh -p {port} plain@{host}   (lines, no screen)\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 46 item 7: the banner names where the class reaches the server, never a bare
    /// `HOST` when an address is known, and says how the presenter comes in.
    #[test]
    fn the_banner_names_the_machine_and_the_presenters_way_in() {
        let any = "0.0.0.0:2222".parse().unwrap();
        let b = banner(any, &["192.0.2.2".into(), "vm".into()]);
        assert!(b.contains("this machine: 192.0.2.2, vm"), "{b}");
        assert!(b.contains("students: ssh -p 2222 class@192.0.2.2"), "{b}");
        assert!(
            b.contains("presenter: ssh -p 2222 class@192.0.2.2   with the presenter passphrase"),
            "{b}"
        );
        assert!(b.contains("ssh -p 2222 plain@192.0.2.2"), "{b}");
        assert!(!b.contains("HOST"), "{b}");
        // Nothing found: HOST, said to be the machine's address.
        let b = banner(any, &[]);
        assert!(
            b.contains("class@HOST") && b.contains("none found here"),
            "{b}"
        );
        // One address listened on: that one, with no list.
        let lo = "127.0.0.1:2300".parse().unwrap();
        assert_eq!(hosts(lo), ["127.0.0.1"]);
        let b = banner(lo, &hosts(lo));
        assert!(
            b.starts_with("students: ssh -p 2300 class@127.0.0.1"),
            "{b}"
        );
        // Every address: what is found is neither the loopback nor blank.
        for h in hosts(any) {
            assert!(!h.is_empty() && !h.contains(char::is_whitespace), "{h}");
            assert!(
                h.parse::<std::net::IpAddr>()
                    .map_or(true, |ip| !ip.is_loopback())
            );
        }
    }
}
