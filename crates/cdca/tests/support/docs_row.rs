//! Rows of the measured tables in `docs/`. A test that measures a row writes
//! it to `target/docs/TABLE/KEY.md`; `scripts/docs.sh` puts a table's rows,
//! sorted by key, between its markers (`<!-- generated:TABLE -->`), and
//! `scripts/docs.sh --check` fails when `docs/` no longer says what the
//! tests measured. Numbers go through [`sig`], so a row changes only when a
//! measurement does.
#![allow(dead_code)]

use std::path::PathBuf;

/// The `target/` directory of the running test binary
/// (`target/<profile>/deps/<binary>`).
fn target_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    exe.ancestors()
        .nth(3)
        .expect("a test binary under target/<profile>/deps")
        .to_path_buf()
}

/// Writes one row of the generated table `table`: the cells joined as a
/// Markdown table row, in `target/docs/{table}/{key}.md`.
pub fn record_row(table: &str, key: &str, cells: &[&str]) {
    let dir = target_dir().join("docs").join(table);
    std::fs::create_dir_all(&dir).expect("target/docs is writable");
    let cells: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
    let row = format!("| {} |\n", cells.join(" | "));
    std::fs::write(dir.join(format!("{key}.md")), row).expect("a row file in target/docs");
}

/// A row of the verification table (docs/verification.md): the problem and
/// its reference, the test, the mesh, the measured value and what the test
/// asserts. `file` is the test file's stem; rows sort by file, then test.
pub fn verification_row(
    file: &str,
    test: &str,
    problem: &str,
    mesh: &str,
    measured: &str,
    asserted: &str,
) {
    let name = format!("`{test}`");
    record_row(
        "verification",
        &format!("{file}-{test}"),
        &[problem, &name, mesh, measured, asserted],
    );
}

/// `x` to `digits` significant digits: fixed point from 1e-3 up, exponent
/// form below (`2.7e-12`).
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = digits.max(1);
    #[allow(clippy::cast_possible_truncation)]
    let magnitude = x.abs().log10().floor() as i32;
    if magnitude < -3 {
        return format!("{:.*e}", digits - 1, x);
    }
    #[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
    let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
    format!("{x:.decimals$}")
}

/// A relative error to one significant digit, or `1e-12` below that (the
/// round-off, which differs between machines).
pub fn tiny(x: f64) -> String {
    if x < 1e-12 {
        "1e-12".to_owned()
    } else {
        sig(x, 1)
    }
}

/// `x` (a ratio) as a signed percentage to `digits` significant digits
/// (`-0.10%`).
pub fn pct(x: f64, digits: usize) -> String {
    let s = sig(100.0 * x, digits);
    if x > 0.0 {
        format!("+{s}%")
    } else {
        format!("{s}%")
    }
}

/// `x` (a ratio) as an unsigned percentage (`0.14%`).
pub fn pct_abs(x: f64, digits: usize) -> String {
    format!("{}%", sig(100.0 * x.abs(), digits))
}
