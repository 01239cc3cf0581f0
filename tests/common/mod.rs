//! What the integration tests share: the binary run as a user runs it.

use std::process::Command;

/// Runs `turntable` with `args`: exit code, stdout, stderr.
pub fn turntable(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}
