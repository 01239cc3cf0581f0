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
