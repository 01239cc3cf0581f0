//! `authorized_keys` files (`--authorized-keys`, `--presenter-keys`), read as OpenSSH's sshd
//! reads them: one key a line, `#` comments, options before the key (separated by commas, a
//! value in double quotes that may hold spaces, commas and `\"`, names in any case). The
//! options that restrict a key here are honoured: `from="pattern-list"` (the client's address
//! against addresses, `address/bits` and `*`/`?` patterns, `!` refusing) and
//! `expiry-time="YYYYMMDD[HHMM[SS]]Z"`. `restrict` and the `no-…` options are taken: they
//! forbid what serve never gives (forwarding, X11, an agent, a user's rc, a terminal on the
//! server's system: the explorer is drawn into the channel whatever the client asked). Every
//! other option is refused by name at start: a key is never let in with its restriction
//! ignored.

use crate::error::Error;
use russh::keys::PublicKey;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr};
use std::path::Path;

/// A key that may get in, and what its options restrict it to.
#[derive(Clone, Debug)]
pub struct Authorized {
    key: PublicKey,
    /// `from="…"`: the addresses it may come from; None for anywhere.
    from: Option<Vec<Pattern>>,
    /// `expiry-time="…"`: the last second (since the epoch, UTC) it gets in.
    expiry: Option<i64>,
}

impl From<PublicKey> for Authorized {
    fn from(key: PublicKey) -> Authorized {
        Authorized {
            key,
            from: None,
            expiry: None,
        }
    }
}

impl Authorized {
    /// Whether `key` is this one, from a client at `ip`, at `now` (seconds since the epoch).
    pub fn admits(&self, key: &PublicKey, ip: IpAddr, now: i64) -> bool {
        self.key.key_data() == key.key_data()
            && self.expiry.is_none_or(|last| now <= last)
            && self.from.as_ref().is_none_or(|p| allowed(p, ip))
    }
}

/// The seconds since the epoch now, as the expiry of a key is compared with.
pub fn now() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| i64::try_from(d.as_secs()).unwrap_or(i64::MAX))
}

/// The keys of an `authorized_keys` file. A line that is not a key, an option refused, or a
/// file that admits nobody (no key, or every key expired) is refused, naming the file and the
/// line.
pub fn authorized_keys(path: &Path) -> Result<Vec<Authorized>, Error> {
    keys_at(path, now())
}

/// [`authorized_keys`], `now` seconds after the epoch.
fn keys_at(path: &Path, now: i64) -> Result<Vec<Authorized>, Error> {
    let text = crate::files::read_bounded(path, 1 << 20)?;
    let shown = crate::files::escape_controls(&path.display().to_string());
    let mut keys = vec![];
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        keys.push(read_line(line).map_err(|why| {
            let why: String = crate::files::escape_controls(&why)
                .chars()
                .take(300)
                .collect();
            Error::invalid(format!("{shown}:{}: {why}", n + 1))
        })?);
    }
    if keys.is_empty() {
        return Err(Error::invalid(format!(
            "{shown}: no key in it: nobody could get in with it"
        )));
    }
    if keys.iter().all(|k| k.expiry.is_some_and(|last| now > last)) {
        return Err(Error::invalid(format!(
            "{shown}: every key in it has expired (expiry-time): nobody could get in with it"
        )));
    }
    Ok(keys)
}

/// One line: a key, or options and a key (each followed by an optional comment).
fn read_line(line: &str) -> Result<Authorized, String> {
    if let Ok(key) = PublicKey::from_openssh(line) {
        return Ok(key.into());
    }
    let (options, rest) = split(line)?;
    let key = PublicKey::from_openssh(rest.trim_start_matches([' ', '\t']))
        .map_err(|e| format!("not a public key: {e}"))?;
    let mut authorized = Authorized::from(key);
    for (name, value) in parse(options)? {
        restrict(&mut authorized, &name, value)?;
    }
    Ok(authorized)
}

/// A line's options and what follows them, as OpenSSH's `sshkey_advance_past_options`: up to
/// the first space or tab outside double quotes, `\"` never closing one.
fn split(line: &str) -> Result<(&str, &str), String> {
    let mut quoted = false;
    let mut chars = line.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        match c {
            '\\' if chars.peek().is_some_and(|&(_, n)| n == '"') => {
                chars.next();
            }
            '"' => quoted = !quoted,
            ' ' | '\t' if !quoted => return Ok((&line[..i], &line[i..])),
            _ => {}
        }
    }
    Err(if quoted {
        "not a public key, and its options leave a quote open".into()
    } else {
        "not a public key".into()
    })
}

/// Options as OpenSSH's `opts_parse` reads them: `name` or `name="value"` (`\"` a quote in
/// it), separated by commas; names lowercased.
fn parse(options: &str) -> Result<Vec<(String, Option<String>)>, String> {
    let mut out = vec![];
    let mut rest = options;
    loop {
        let end = rest.find([',', '=']).unwrap_or(rest.len());
        let name = rest[..end].to_ascii_lowercase();
        if name.is_empty() {
            return Err(format!("an empty option in {options}"));
        }
        rest = &rest[end..];
        let value = match rest.strip_prefix('=') {
            None => None,
            Some(v) => {
                let v = v
                    .strip_prefix('"')
                    .ok_or_else(|| format!("option {name}=: its value must be in double quotes"))?;
                let (value, after) = dequote(v)
                    .ok_or_else(|| format!("option {name}=: its value's quote is never closed"))?;
                rest = after;
                Some(value)
            }
        };
        out.push((name, value));
        match rest.strip_prefix(',') {
            Some(r) => rest = r,
            None if rest.is_empty() => return Ok(out),
            None => return Err(format!("options: a comma expected before {rest}")),
        }
    }
}

/// A quoted value up to its closing quote (`\"` a quote), and what follows the quote.
fn dequote(s: &str) -> Option<(String, &str)> {
    let mut value = String::new();
    let mut chars = s.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        match c {
            '\\' if chars.peek().is_some_and(|&(_, n)| n == '"') => {
                chars.next();
                value.push('"');
            }
            '"' => return Some((value, &s[i + 1..])),
            c => value.push(c),
        }
    }
    None
}

/// Applies one option to `key`, or says why it is refused.
fn restrict(key: &mut Authorized, name: &str, value: Option<String>) -> Result<(), String> {
    const FLAGS: [&str; 11] = [
        "restrict",
        "no-agent-forwarding",
        "no-port-forwarding",
        "no-pty",
        "no-user-rc",
        "no-x11-forwarding",
        "agent-forwarding",
        "port-forwarding",
        "pty",
        "user-rc",
        "x11-forwarding",
    ];
    match (name, value) {
        (flag, None) if FLAGS.contains(&flag) => Ok(()),
        (flag, Some(_)) if FLAGS.contains(&flag) => Err(format!("option {flag} takes no value")),
        ("from" | "expiry-time", None) => Err(format!("option {name} needs a value (\"…\")")),
        ("from", Some(_)) if key.from.is_some() => Err("option from= given twice".into()),
        ("from", Some(v)) => {
            key.from = Some(patterns(&v).map_err(|why| format!("from=\"{v}\": {why}"))?);
            Ok(())
        }
        ("expiry-time", Some(v)) => {
            let t = expiry(&v).map_err(|why| format!("expiry-time=\"{v}\": {why}"))?;
            // As OpenSSH: given twice, the earlier.
            key.expiry = Some(key.expiry.map_or(t, |e| e.min(t)));
            Ok(())
        }
        ("cert-authority", _) => Err(
            "cert-authority: a certificate authority, not a key (serve takes plain keys only)"
                .into(),
        ),
        (name, _) => Err(format!(
            "option {name} is not honoured by turntable serve (it honours from=, expiry-time=, \
             restrict and the no-… options), and a key is never let in with its restriction \
             ignored: remove the option or the line"
        )),
    }
}

/// One entry of a `from=` list.
#[derive(Clone, Debug, PartialEq)]
struct Pattern {
    /// `!`: a client it matches is refused, whatever else matches.
    negated: bool,
    what: Match,
}

#[derive(Clone, Debug, PartialEq)]
enum Match {
    /// An address and the bits of it that must agree (all of them for a bare address).
    Net(IpAddr, u8),
    /// `*` any run of characters, `?` any one, against the address as written (lowercase).
    Glob(String),
}

/// A `from=` list as OpenSSH's `addr_match_list` reads it, without host names (serve looks
/// none up, as sshd with its default `UseDNS no`): an entry naming a host is refused rather
/// than never matching.
fn patterns(list: &str) -> Result<Vec<Pattern>, String> {
    list.split(',')
        .map(|entry| {
            let (negated, p) = entry
                .strip_prefix('!')
                .map_or((false, entry), |p| (true, p));
            let what = if let Some((addr, bits)) = p.split_once('/') {
                let addr: IpAddr = addr
                    .parse()
                    .map_err(|_| format!("{p}: not an address/bits"))?;
                let bits: u8 = bits
                    .parse()
                    .ok()
                    .filter(|&b| b <= width(addr))
                    .ok_or_else(|| format!("{p}: bits from 0 to {}", width(addr)))?;
                if masked(addr, bits) != addr {
                    return Err(format!(
                        "{p}: the address has bits set beyond the first {bits}"
                    ));
                }
                Match::Net(addr, bits)
            } else if let Ok(addr) = p.parse::<IpAddr>() {
                Match::Net(addr, width(addr))
            } else if !p.is_empty()
                && p.chars()
                    .all(|c| c.is_ascii_hexdigit() || matches!(c, '.' | ':' | '*' | '?'))
            {
                Match::Glob(p.to_ascii_lowercase())
            } else {
                return Err(format!(
                    "{p:?}: not an address, address/bits or pattern of one (serve looks up no \
                     host names)"
                ));
            };
            Ok(Pattern { negated, what })
        })
        .collect()
}

fn width(addr: IpAddr) -> u8 {
    if addr.is_ipv4() { 32 } else { 128 }
}

/// `addr` with all but its first `bits` bits cleared.
fn masked(addr: IpAddr, bits: u8) -> IpAddr {
    match addr {
        IpAddr::V4(a) => {
            let mask = u32::MAX.checked_shl(32 - u32::from(bits)).unwrap_or(0);
            IpAddr::V4(Ipv4Addr::from(u32::from(a) & mask))
        }
        IpAddr::V6(a) => {
            let mask = u128::MAX.checked_shl(128 - u32::from(bits)).unwrap_or(0);
            IpAddr::V6(Ipv6Addr::from(u128::from(a) & mask))
        }
    }
}

/// Whether a client at `ip` may use a key with these `from=` patterns: refused if a negated
/// one matches, let in if another does (an IPv4 client over IPv6 is its IPv4 address, as sshd
/// takes it).
fn allowed(patterns: &[Pattern], ip: IpAddr) -> bool {
    let ip = ip.to_canonical();
    let text = ip.to_string();
    let mut any = false;
    for p in patterns {
        let hit = match &p.what {
            Match::Net(net, bits) => width(*net) == width(ip) && masked(ip, *bits) == *net,
            Match::Glob(g) => glob(g.as_bytes(), text.as_bytes()),
        };
        if hit && p.negated {
            return false;
        }
        any |= hit;
    }
    any
}

/// `*` and `?` wildcards, as OpenSSH's `match_pattern`.
fn glob(pattern: &[u8], text: &[u8]) -> bool {
    let (mut p, mut t) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while t < text.len() {
        match pattern.get(p) {
            Some(b'*') => {
                star = Some((p, t));
                p += 1;
            }
            Some(&c) if c == b'?' || c == text[t] => {
                p += 1;
                t += 1;
            }
            _ => match star {
                Some((sp, st)) => {
                    star = Some((sp, st + 1));
                    p = sp + 1;
                    t = st + 1;
                }
                None => return false,
            },
        }
    }
    pattern[p..].iter().all(|&c| c == b'*')
}

/// An `expiry-time` as OpenSSH's `parse_absolute_time` reads it: `YYYYMMDD`, `YYYYMMDDHHMM` or
/// `YYYYMMDDHHMMSS`, in UTC when it ends in `Z` (or `UTC`). Without, sshd reads the server's
/// local time zone, which turntable does not read: such a time is refused, not guessed.
fn expiry(text: &str) -> Result<i64, String> {
    let upper = text.to_ascii_uppercase();
    let Some(digits) = upper
        .strip_suffix('Z')
        .or_else(|| upper.strip_suffix("UTC"))
    else {
        return Err(format!(
            "a time in the server's local zone, which serve does not read: write it in UTC, \
             ending in Z ({text}Z)"
        ));
    };
    if !matches!(digits.len(), 8 | 12 | 14) || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err("not YYYYMMDD[HHMM[SS]]Z".into());
    }
    let field = |a: usize, b: usize| digits.get(a..b).map_or(Ok(0), str::parse::<i64>);
    let bad = |_| "not YYYYMMDD[HHMM[SS]]Z".to_string();
    let (y, m, d) = (
        field(0, 4).map_err(bad)?,
        field(4, 6).map_err(bad)?,
        field(6, 8).map_err(bad)?,
    );
    let (h, min, s) = (
        field(8, 10).map_err(bad)?,
        field(10, 12).map_err(bad)?,
        field(12, 14).map_err(bad)?,
    );
    if !(1..=12).contains(&m) || d < 1 || d > days_in(y, m) || h > 23 || min > 59 || s > 59 {
        return Err("not a date and time".into());
    }
    Ok(days_from_civil(y, m, d) * 86_400 + h * 3600 + min * 60 + s)
}

fn days_in(y: i64, m: i64) -> i64 {
    let leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    match m {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Days from 1970-01-01 to the date (proleptic Gregorian; Hinnant's `days_from_civil`).
fn days_from_civil(y: i64, m: i64, d: i64) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use russh::keys::PrivateKey;
    use russh::keys::ssh_key::private::Ed25519Keypair;

    fn line() -> String {
        let key = PrivateKey::from(Ed25519Keypair::from_seed(&[7; 32]));
        key.public_key().to_openssh().unwrap()
    }

    fn v4(a: u32) -> IpAddr {
        IpAddr::V4(std::net::Ipv4Addr::from(a))
    }

    fn ip(s: &str) -> IpAddr {
        s.parse().unwrap()
    }

    /// The file's keys with `now` at 2026-01-01, or its refusal in words.
    fn read(text: &str) -> Result<Vec<Authorized>, String> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keys");
        std::fs::write(&path, text).unwrap();
        keys_at(&path, JAN_2026).map_err(|e| e.to_string())
    }

    const JAN_2026: i64 = 1_767_225_600;

    /// Options are read as OpenSSH reads them; those not honoured are refused by name, and a
    /// file that admits nobody is refused.
    #[test]
    fn options_are_honoured_or_refused_by_name() {
        let line = line();
        for ok in [
            line.clone(),
            format!("restrict {line}"),
            format!("RESTRICT,pty,No-Port-Forwarding {line} a comment"),
            format!("from=\"10.9.9.9\" {line}"),
            format!("from=\"10.0.0.0/8,!10.9.*,fe80::/10\",restrict {line}"),
            format!("expiry-time=\"20300101Z\" {line}"),
            format!("expiry-time=\"203001011200utc\"\t{line}"),
            format!("expiry-time=\"20200101Z\" {line}\n{line}"),
        ] {
            assert!(!read(&ok).unwrap().is_empty(), "{ok}");
        }
        for (bad, said) in [
            (
                format!("command=\"echo hi\" {line}"),
                "option command is not honoured",
            ),
            (
                format!("command=\"a \\\" b, c\" {line}"),
                "option command is not",
            ),
            (
                format!("from=\"*.example.com\" {line}"),
                "serve looks up no host names",
            ),
            (format!("from=10.9.9.9 {line}"), "must be in double quotes"),
            (format!("from=\"10.0.0.1/8\" {line}"), "bits set beyond"),
            (format!("from=\"10.0.0.0/33\" {line}"), "bits from 0 to 32"),
            (
                format!("from=\"10.0.0.1\",from=\"10.0.0.2\" {line}"),
                "from= given twice",
            ),
            (format!("from {line}"), "needs a value"),
            (format!("restrict=\"x\" {line}"), "takes no value"),
            (
                format!("expiry-time=\"20300101\" {line}"),
                "the server's local zone",
            ),
            (
                format!("expiry-time=\"20300230Z\" {line}"),
                "not a date and time",
            ),
            (format!("expiry-time=\"2030Z\" {line}"), "not YYYYMMDD"),
            (
                format!("expiry-time=\"20200101Z\" {line}"),
                "every key in it has expired",
            ),
            (
                format!("restrict,cert-authority {line}"),
                "cert-authority: a certificate",
            ),
            (format!("from=\"10.0.0.1 {line}"), "leave a quote open"),
            ("ssh-ed25519 AAAAnotbase64 x".into(), "not a public key"),
            ("# nobody\n\n".into(), "nobody could get in"),
        ] {
            let e = read(&bad).unwrap_err();
            assert!(e.contains(said), "{bad}: {e}");
            assert!(e.contains(":1: ") || e.contains("nobody"), "{e}");
        }
    }

    /// `from=` as sshd matches it: addresses, nets, wildcards; a negated match refuses whatever
    /// else matched; nothing matching refuses.
    #[test]
    fn from_matches_as_sshd() {
        let key = read(&line()).unwrap()[0].key.clone();
        let with = |from: &str| read(&format!("from=\"{from}\" {}", line())).unwrap()[0].clone();
        for (from, client, admitted) in [
            ("10.9.9.9", "127.0.0.1", false),
            ("10.9.9.9", "10.9.9.9", true),
            ("127.0.0.1", "127.0.0.1", true),
            ("127.0.0.1", "::ffff:127.0.0.1", true),
            ("127.*", "127.0.0.1", true),
            ("127.0.0.?", "127.0.0.1", true),
            ("127.0.0.?", "127.0.0.10", false),
            ("10.0.0.0/8,!10.9.*", "10.1.2.3", true),
            ("10.0.0.0/8,!10.9.*", "10.9.2.3", false),
            ("!10.9.*", "10.1.2.3", false),
            ("*,!127.0.0.1", "127.0.0.1", false),
            ("fe80::/10", "fe80::1", true),
            ("fe80::/10", "10.0.0.1", false),
            ("fe80:0:0::1", "fe80::1", true),
            ("0.0.0.0/0", "192.168.1.1", true),
        ] {
            assert_eq!(
                with(from).admits(&key, ip(client), JAN_2026),
                admitted,
                "from={from} for {client}"
            );
        }
    }

    /// A key gets in up to the second its expiry names, and not after.
    #[test]
    fn an_expired_key_is_refused() {
        let k = read(&format!("expiry-time=\"20260101000010Z\" {}", line())).unwrap()[0].clone();
        let at = |t| k.admits(&k.key, ip("127.0.0.1"), t);
        assert!(at(JAN_2026 + 10));
        assert!(!at(JAN_2026 + 11));
        // Given twice, the earlier holds.
        let k = read(&format!(
            "expiry-time=\"20300101Z\",expiry-time=\"20260101Z\",expiry-time=\"20290101Z\" {}",
            line()
        ))
        .unwrap()[0]
            .clone();
        assert_eq!(k.expiry, Some(JAN_2026));
        assert_eq!(expiry("19700101Z"), Ok(0));
        assert_eq!(expiry("20000229235959Z"), Ok(951_868_799));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Options written as OpenSSH writes them (values quoted, `"` as `\"`, spaces and commas
        /// inside) are read back as they were, and the key after them is found.
        #[test]
        fn quoted_options_read_back(
            opts in prop::collection::vec(
                ("[a-z][a-z-]{0,12}", prop::option::of("[ a-z0-9,\"!*.=\\\\\t-]{0,16}")),
                1..5,
            )
        ) {
            let written: Vec<String> = opts
                .iter()
                .map(|(n, v)| match v {
                    None => n.clone(),
                    Some(v) => format!("{n}=\"{}\"", v.replace('"', "\\\"")),
                })
                .collect();
            // A backslash before the value's closing quote makes it an escaped quote (OpenSSH's
            // reading too): no such value is written.
            prop_assume!(opts.iter().all(|(_, v)| v.as_ref().is_none_or(|v| !v.ends_with('\\'))));
            let text = format!("{} {} comment", written.join(","), line());
            let (options, rest) = split(&text).unwrap();
            prop_assert_eq!(rest.trim_start(), format!("{} comment", line()));
            prop_assert_eq!(parse(options).unwrap(), opts);
        }

        /// A net holds exactly the addresses whose first bits are its own; `!net` refuses them and
        /// nothing else lets in the rest; a wildcard made from the address matches it.
        #[test]
        fn nets_and_wildcards_match_their_addresses(a in any::<u32>(), b in any::<u32>(), bits in 0u8..=32) {
            let net = masked(v4(a), bits);
            let pats = patterns(&format!("{net}/{bits}")).unwrap();
            let mask = u32::MAX.checked_shl(32 - u32::from(bits)).unwrap_or(0);
            let inside = (a ^ b) & mask == 0;
            prop_assert_eq!(allowed(&pats, v4(b)), inside);
            let neg = patterns(&format!("*,!{net}/{bits}")).unwrap();
            prop_assert_eq!(allowed(&neg, v4(b)), !inside);
            let text = v4(b).to_string();
            let wild: String = text
                .chars()
                .enumerate()
                .map(|(i, c)| if (a >> (i % 32)) & 1 == 1 { '?' } else { c })
                .collect();
            prop_assert!(allowed(&patterns(&wild).unwrap(), v4(b)), "{}", wild);
            let star = format!("{}*", &text[..text.len() / 2]);
            prop_assert!(allowed(&patterns(&star).unwrap(), v4(b)), "{}", star);
        }
    }
}
