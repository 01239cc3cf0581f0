//! Who may come in, and as what: the host key (made once, kept 0600 under the XDG data
//! folder), the authorized keys, the passphrases (the class's and the presenter's: given, or
//! made from the system's randomness and printed at start), compared in constant time.

use crate::error::Error;
use russh::keys::ssh_key::{HashAlg, LineEnding, private::Ed25519Keypair};
use russh::keys::{PrivateKey, PublicKey};
use std::path::{Path, PathBuf};

/// Where the host key lives: `$XDG_DATA_HOME/turntable/ssh_host_ed25519_key`
/// (`~/.local/share/…` when XDG_DATA_HOME is unset).
pub fn host_key_path(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> Option<PathBuf> {
    let data = var("XDG_DATA_HOME")
        .map(PathBuf::from)
        .filter(|p| p.is_absolute())
        .or_else(|| var("HOME").map(|h| PathBuf::from(h).join(".local/share")))?;
    Some(data.join("turntable").join("ssh_host_ed25519_key"))
}

/// The host key at `path`, made there (Ed25519, 0600) the first time.
pub fn host_key(path: &Path) -> Result<PrivateKey, Error> {
    let shown = crate::files::escape_controls(&path.display().to_string());
    if path.exists() {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(path)
            .map_err(|e| Error::Io {
                what: format!("reading the host key {shown}"),
                source: std::sync::Arc::new(e),
            })?
            .permissions()
            .mode();
        // As sshd: a host key others may read is no longer the server's alone.
        if mode & 0o077 != 0 {
            return Err(Error::invalid(format!(
                "{shown}: the host key is readable by others (mode {:o}): `chmod 600` it",
                mode & 0o777
            )));
        }
        let text = crate::files::read_bounded(path, 64 * 1024)?;
        let key = PrivateKey::from_openssh(text.as_bytes())
            .map_err(|e| Error::invalid(format!("{shown}: not an OpenSSH private key: {e}")))?;
        if key.is_encrypted() {
            return Err(Error::invalid(format!(
                "{shown}: the host key is encrypted (passphrase-protected), and serve cannot \
                 ask for its passphrase: give an unencrypted key"
            )));
        }
        return weak(key.public_key())
            .map(|why| Err(Error::invalid(format!("{shown}: {why}"))))
            .unwrap_or(Ok(key));
    }
    let mut seed = [0u8; 32];
    random(&mut seed)?;
    let key = PrivateKey::from(Ed25519Keypair::from_seed(&seed));
    let text = key
        .to_openssh(LineEnding::LF)
        .map_err(|e| Error::Failed(format!("encoding the host key: {e}")))?;
    crate::files::write_secret(path, text.as_bytes()).map_err(|e| Error::Io {
        what: format!("writing the host key {shown}"),
        source: std::sync::Arc::new(e),
    })?;
    Ok(key)
}

/// Why a key is too weak to serve with, if it is (as OpenSSH: RSA under 2048 bits, DSA).
fn weak(key: &PublicKey) -> Option<String> {
    use russh::keys::Algorithm;
    if let Some(rsa) = key.key_data().rsa()
        && rsa.key_size() < 2048
    {
        return Some(format!(
            "an RSA key of {} bits is too weak (2048 at least)",
            rsa.key_size()
        ));
    }
    (key.algorithm() == Algorithm::Dsa).then(|| "a DSA key is too weak".to_string())
}

/// The key's SHA-256 fingerprint, as `ssh` shows it.
pub fn fingerprint(key: &PrivateKey) -> String {
    key.public_key().fingerprint(HashAlg::Sha256).to_string()
}

fn random(buf: &mut [u8]) -> Result<(), Error> {
    getrandom::getrandom(buf).map_err(|e| Error::Failed(format!("the system's randomness: {e}")))
}

/// Words a class can type, from the system's randomness: four of 256, 32 bits.
pub fn passphrase() -> Result<String, Error> {
    const SYL: [&str; 16] = [
        "ba", "ke", "di", "lo", "mu", "ra", "te", "vo", "si", "na", "po", "gu", "fe", "ji", "ko",
        "ze",
    ];
    let mut b = [0u8; 4];
    random(&mut b)?;
    let word = |x: u8| format!("{}{}", SYL[usize::from(x >> 4)], SYL[usize::from(x & 15)]);
    Ok(b.iter().map(|&x| word(x)).collect::<Vec<_>>().join("-"))
}

/// Whether `given` is `expected`, in time that depends on their lengths only.
pub fn same(given: &str, expected: &str) -> bool {
    let (a, b) = (given.as_bytes(), expected.as_bytes());
    let diff = a
        .iter()
        .zip(b.iter().cycle())
        .fold(a.len() ^ b.len(), |d, (x, y)| d | usize::from(x ^ y));
    diff == 0 && !b.is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passphrases_compare_whole() {
        assert!(same("ba-ke", "ba-ke"));
        assert!(!same("ba-k", "ba-ke"));
        assert!(!same("ba-kee", "ba-ke"));
        assert!(!same("", ""));
        let p = passphrase().unwrap();
        assert_eq!(p.split('-').count(), 4);
        assert_ne!(p, passphrase().unwrap());
    }

    #[test]
    fn the_host_key_is_made_once_and_kept_private() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t/key");
        let a = host_key(&path).unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o600);
        let b = host_key(&path).unwrap();
        assert_eq!(fingerprint(&a), fingerprint(&b));
        assert!(fingerprint(&a).starts_with("SHA256:"));
        let home = |v: &str| (v == "HOME").then(|| "/h".into());
        assert_eq!(
            host_key_path(home),
            Some(PathBuf::from(
                "/h/.local/share/turntable/ssh_host_ed25519_key"
            ))
        );
    }
}
