//! `turntable serve`'s settings, checked at start: what no class can run on exits 2 with a
//! clear message before anything listens (sizes and counts of 0, empty or equal passphrases, a
//! host key others may read, encrypted or weak, a key file that admits nobody or restricts its
//! keys in ways serve cannot honour); and a flag's value echoed in a parse error has its control
//! characters escaped.

use crate::common::turntable;
use std::os::unix::fs::PermissionsExt;

/// A host key protected by the passphrase `words` (made by `ssh-keygen -t ed25519 -N words`).
const ENCRYPTED: &str = "-----BEGIN OPENSSH PRIVATE KEY-----
b3BlbnNzaC1rZXktdjEAAAAACmFlczI1Ni1jdHIAAAAGYmNyeXB0AAAAGAAAABCCrJ+5be
5h/LobsPydMxv8AAAAEAAAAAEAAAAzAAAAC3NzaC1lZDI1NTE5AAAAIJaDcbp/xDakiHOU
EhWHaxdn744kVoQeOWdqHZUrIJwaAAAAkO9Zl4bUhysfanKGjfvv+3rd4o1ejLcJg/hjd6
nAiOs0frk+qDwPeSAUPc5Jxua7Kv4MbTC0dtS8tU/nQs+q6k1X//5ENvs3w9P0FszWp/jj
Fo9mmdgC/k+2sdjtDUmmSEhcfLHXkWaN+FbGQtB8mfL124uvGzG3RU7Ye8Q/rFkz0n4hjm
TB2JEyVo3ElgL1fg==
-----END OPENSSH PRIVATE KEY-----
";

/// A 1024-bit RSA host key (`ssh-keygen -t rsa -b 1024`).
const RSA_1024: &str = "-----BEGIN OPENSSH PRIVATE KEY-----
b3BlbnNzaC1rZXktdjEAAAAABG5vbmUAAAAEbm9uZQAAAAAAAAABAAAAlwAAAAdzc2gtcn
NhAAAAAwEAAQAAAIEAwxK6FI4Ln0P3o5VLt81xfbDPxLa9O75vpNWtBC67cPbienZUMBr9
s8F7RGYEu/NNtRbRQ+ZXcI+1lB95qTTIi1+OEM/uPRylwcM7V76UsF0UD9u6gP88MGChAG
7Z5tAxu6Su72EfYMd5M7cIspTiI/lhRQI110/Q/sGVMbX2bqMAAAH47NYl7ezWJe0AAAAH
c3NoLXJzYQAAAIEAwxK6FI4Ln0P3o5VLt81xfbDPxLa9O75vpNWtBC67cPbienZUMBr9s8
F7RGYEu/NNtRbRQ+ZXcI+1lB95qTTIi1+OEM/uPRylwcM7V76UsF0UD9u6gP88MGChAG7Z
5tAxu6Su72EfYMd5M7cIspTiI/lhRQI110/Q/sGVMbX2bqMAAAADAQABAAAAgAsVqVU5rR
djuVKmTSMonWZTAbtf1ujqLVXkfmxaa3RD0yK6TpZdMkVgnSyJz4MOlD/SCBofoKBYyiyc
jUE8KpkHVbvRnyo8Pb7PMCbU2PQ9c6x2zXFnVJvka7ohtFi0g1EIXFhFSWS0D2nw09zOmU
3v3BeKZ+wzihExCxBCb3HBAAAAQG0Kz7u8zRWwi1JssihcJhDQotod8u8ZOuiBwmjpEvL5
XfJ75Z8zOBT5XEgEVJG6d64AUFf/lp810or+LF0LxCwAAABBAPXfD1JlMyT6vTDSaiK87R
bHiRIt5PqzXHAGVu528n7Set1libmApJpY0EwvumkX/Yn5nct3Z6aFjXt0xPtONUkAAABB
AMsb9A+dq/erW6yajzlqzHVTROYD7wGleoC3W9xVCkGydrIE4qfH2B+lEBV7Xb3uIoFp5O
k9BQI65NLlN0gDgIsAAAAAAQID
-----END OPENSSH PRIVATE KEY-----
";

/// `turntable serve` with `args` and a fresh host key under `dir`: its exit code and stderr.
fn serve(dir: &std::path::Path, args: &[&str]) -> (i32, String) {
    let host = dir.join("host");
    let mut all = vec!["serve", "--listen", "127.0.0.1:0", "--host-key"];
    let host = host.to_str().unwrap().to_string();
    all.push(&host);
    all.extend_from_slice(args);
    let (code, _, err) = turntable(&all);
    (code, err)
}

fn refused(dir: &std::path::Path, args: &[&str], said: &str) {
    let (code, err) = serve(dir, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(err.contains(said), "{args:?}: {err}");
}

#[test]
fn sizes_and_counts_of_zero_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(d, &["--max-size", "80x0"], "--max-size 80x0: a side of 0");
    refused(d, &["--max-size", "0x24"], "--max-size 0x24: a side of 0");
    for flag in [
        "--max-sessions",
        "--per-minute",
        "--max-waiting",
        "--max-waiting-per-address",
        "--login-grace",
        "--shell-grace",
        "--idle",
    ] {
        refused(d, &[flag, "0"], &format!("invalid value '0' for '{flag}"));
    }
}

#[test]
fn passphrases_empty_or_the_same_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(d, &["--passphrase", ""], "--passphrase is empty");
    refused(
        d,
        &["--presenter-passphrase", " "],
        "--presenter-passphrase is empty",
    );
    refused(
        d,
        &["--passphrase", "ba-ke", "--presenter-passphrase", "ba-ke"],
        "every student would present",
    );
}

#[test]
fn host_keys_others_may_read_encrypted_or_weak_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let host = dir.path().join("host");
    for (text, mode, said) in [
        (ENCRYPTED, 0o600, "encrypted (passphrase-protected)"),
        (RSA_1024, 0o600, "an RSA key of 1024 bits is too weak"),
        (RSA_1024, 0o644, "readable by others (mode 644)"),
    ] {
        let _ = std::fs::remove_file(&host);
        std::fs::write(&host, text).unwrap();
        std::fs::set_permissions(&host, std::fs::Permissions::from_mode(mode)).unwrap();
        refused(dir.path(), &[], said);
    }
}

#[test]
fn key_files_that_admit_nobody_or_restrict_unhonoured_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let keys = d.join("keys");
    let k = keys.to_str().unwrap();
    let line = "ssh-ed25519 AAAAC3NzaC1lZDI1NTE5AAAAIJdD7y3aLq454yWBdwLWbieU1ebz9/cu7/QEXn9OIeZJ";
    for (text, said) in [
        (String::new(), "nobody could get in"),
        (
            format!("from=\"*.example.com\" {line}"),
            "serve looks up no host names",
        ),
        (
            format!("expiry-time=\"20200101Z\" {line}"),
            "every key in it has expired",
        ),
        (
            format!("cert-authority {line}"),
            "cert-authority: a certificate authority",
        ),
        (
            format!("command=\"echo hi\" {line}"),
            "option command is not honoured",
        ),
    ] {
        std::fs::write(&keys, text).unwrap();
        refused(d, &["--authorized-keys", k], said);
        refused(d, &["--presenter-keys", k], said);
    }
}

/// A flag's value echoed by a parse error reaches the terminal with its control characters
/// escaped: an OSC that would set the title, a C1 CSI.
#[test]
fn parse_errors_escape_the_values_they_echo() {
    let (code, _, err) = turntable(&["run", "--xi0", "1\x1b]0;X\x07"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--xi0") && !err.contains('\x1b') && !err.contains('\x07'),
        "{err}"
    );
    let (code, _, err) = turntable(&["run", "--gamma", "\u{9b}31m"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        !err.contains('\u{9b}') && err.contains("\\u{9b}31m"),
        "{err}"
    );
    assert!(!err.chars().any(|c| c.is_control() && c != '\n'), "{err}");
}
