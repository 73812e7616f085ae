//! A finished study's table summed up per layout: runs, how many linked
//! and at which steps, the first links' load over the run's peak, what
//! they join, how many converged at every step, and the outcomes (the
//! held-out pairs' tables of `docs/fracture-model.md`; a study without a
//! `flaws.layout` axis is one group, `all`); and its first links by the
//! kinds of crack that made them ([`by_crack_kind`]).

use super::flaws::Layout;
use super::row::Table;

/// Header lines of [`by_layout`]'s Markdown table.
pub const HEADER: &str = "| layout | runs | linked (first link at) | link load / peak | what the first link joins | every step converged | outcomes |\n\
                          | --- | --- | --- | --- | --- | --- | --- |\n";

/// One Markdown row per layout, in the order of [`Layout::ALL`] (each
/// row's key, `1-coplanar`, sorts in that order).
pub fn by_layout(table: &Table) -> Vec<(String, String)> {
    groups(table)
        .iter()
        .enumerate()
        .map(|(k, (label, rows))| {
            let key = format!("{}-{}", k + 1, label.replace(", ", "-").replace(' ', "-"));
            (key, row(table, label, rows))
        })
        .collect()
}

/// The rows of each layout (or `all`), in the order of [`Layout::ALL`].
fn groups(table: &Table) -> Vec<(String, Vec<usize>)> {
    let column = table.column("flaws.layout");
    let mut groups: Vec<(usize, String, Vec<usize>)> = Vec::new();
    for r in 0..table.rows.len() {
        let name = column.map_or("all", |c| table.rows[r][c].as_str());
        let (rank, label) = match Layout::from_name(name) {
            Some(l) => (
                Layout::ALL.iter().position(|x| *x == l).unwrap_or_default(),
                l.label(),
            ),
            None => (Layout::ALL.len(), name),
        };
        match groups.iter_mut().find(|g| g.1 == label) {
            Some(g) => g.2.push(r),
            None => groups.push((rank, label.to_owned(), vec![r])),
        }
    }
    groups.sort_by_key(|g| g.0);
    groups
        .into_iter()
        .map(|(_, label, rows)| (label, rows))
        .collect()
}

/// The first link's load over the run's peak, per row that linked.
fn link_over_peak(table: &Table, rows: &[usize]) -> Vec<f64> {
    rows.iter()
        .filter_map(|&r| {
            let link: f64 = table.cell(r, "link_load_factor").parse().ok()?;
            let peak: f64 = table.cell(r, "peak_load_factor").parse().ok()?;
            (peak > 0.0).then(|| link / peak)
        })
        .collect()
}

/// The group's Markdown row.
fn row(table: &Table, label: &str, rows: &[usize]) -> String {
    let cell = |r: usize, c: &str| table.cell(r, c);
    let mut firsts: Vec<usize> = rows
        .iter()
        .filter_map(|&r| cell(r, "link_step").parse().ok())
        .collect();
    firsts.sort_unstable();
    let linked = match (firsts.first(), firsts.last()) {
        (Some(a), Some(b)) if a == b => format!("{} (step {a})", firsts.len()),
        (Some(a), Some(b)) => format!("{} (steps {a}–{b})", firsts.len()),
        _ => "0".to_owned(),
    };
    let ratios = link_over_peak(table, rows);
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(a, b), &v| (a.min(v), b.max(v)));
    let load = if ratios.is_empty() {
        "–".to_owned()
    } else if hi - lo < 5e-3 {
        format!("{lo:.2}")
    } else {
        format!("{lo:.2}–{hi:.2}")
    };
    let joins = counted(rows.iter().map(|&r| cell(r, "link_joins")));
    let converged = rows
        .iter()
        .filter(|&&r| cell(r, "every_step_converged") == "true")
        .count();
    let outcomes = counted(rows.iter().map(|&r| cell(r, "outcome")));
    format!(
        "| {label} | {} | {linked} | {load} | {} | {converged} | {} |\n",
        rows.len(),
        if joins.is_empty() { "–" } else { &joins },
        outcomes
    )
}

/// "N name" for each non-empty name, most first, then by name.
fn counted<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let mut counts: Vec<(usize, &str)> = Vec::new();
    for n in names.filter(|n| !n.is_empty()) {
        match counts.iter_mut().find(|c| c.1 == n) {
            Some(c) => c.0 += 1,
            None => counts.push((1, n)),
        }
    }
    counts.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(b.1)));
    let parts: Vec<String> = counts.iter().map(|(n, k)| format!("{n} {k}")).collect();
    parts.join(", ")
}

/// Header lines of [`by_crack_kind`]'s Markdown table.
pub const KIND_HEADER: &str = "| layout | through tensile cracks alone | through tensile and shear cracks | through shear cracks alone |\n\
                               | --- | --- | --- | --- |\n";

/// What kind of crack made a first link, by the two parts it joins
/// (`link_joins`, as `wing–flaw`): tensile cracks (wings) alone, tensile
/// and shear cracks, or shear cracks alone (secondary cracks, and cracks
/// started in the intact rock, which the rock's Mohr–Coulomb line starts
/// in shear under compression); a flaw is neither. `None` for a link of
/// two flaws.
pub fn crack_kind(joins: &str) -> Option<usize> {
    let (mut tensile, mut shear) = (false, false);
    for part in joins.split('–') {
        match part {
            "wing" => tensile = true,
            "secondary" | "intact" => shear = true,
            _ => {}
        }
    }
    match (tensile, shear) {
        (true, false) => Some(0),
        (true, true) => Some(1),
        (false, true) => Some(2),
        (false, false) => None,
    }
}

/// One Markdown row per layout: for each kind of first link
/// ([`crack_kind`]), how many runs linked so and their mean link load over
/// the run's peak (Park & Bobet 2009 find wings alone need the least
/// stress and shear cracks alone the most).
pub fn by_crack_kind(table: &Table) -> Vec<(String, String)> {
    groups(table)
        .iter()
        .enumerate()
        .map(|(k, (label, rows))| {
            let cells: Vec<String> = (0..3)
                .map(|kind| {
                    let mine: Vec<usize> = rows
                        .iter()
                        .copied()
                        .filter(|&r| crack_kind(table.cell(r, "link_joins")) == Some(kind))
                        .collect();
                    let ratios = link_over_peak(table, &mine);
                    if ratios.is_empty() {
                        "–".to_owned()
                    } else {
                        let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
                        format!("{}: {mean:.2} of the peak", ratios.len())
                    }
                })
                .collect();
            let key = format!("{}-{}", k + 1, label.replace(", ", "-").replace(' ', "-"));
            (key, format!("| {label} | {} |\n", cells.join(" | ")))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three rows of two layouts: the groups in the layouts' order, their
    /// links' steps as a span, the joins and outcomes most first.
    #[test]
    fn rows_are_summed_up_per_layout_in_order() {
        let text = "point,flaws.layout,outcome,every_step_converged,link_step,link_joins,link_load_factor,peak_load_factor\n\
                    1,stepped,through,true,5,wing–wing,0.5,1.0\n\
                    2,overlapping_mirrored,through,false,,,,0.7\n\
                    3,stepped,max_steps,true,43,secondary–wing,0.9,1.0\n\
                    4,stepped,through,true,12,wing–wing,0.4,0.5\n";
        let table = Table::parse(text).expect("parses");
        let rows = by_layout(&table);
        assert_eq!(
            rows,
            [
                (
                    "1-stepped".to_owned(),
                    "| stepped | 3 | 3 (steps 5–43) | 0.50–0.90 | 2 wing–wing, 1 secondary–wing | 3 | 2 through, 1 max_steps |\n"
                        .to_owned()
                ),
                (
                    "2-overlapping-mirrored".to_owned(),
                    "| overlapping, mirrored | 1 | 0 | – | – | 0 | 1 through |\n".to_owned()
                ),
            ]
        );
        // wing–wing twice (0.5 and 0.8 of the peak), secondary–wing once
        assert_eq!(
            by_crack_kind(&table)[0].1,
            "| stepped | 2: 0.65 of the peak | 1: 0.90 of the peak | – |\n"
        );
        assert_eq!(crack_kind("intact–flaw"), Some(2));
        assert_eq!(crack_kind("wing–intact"), Some(1));
        assert_eq!(crack_kind("flaw–flaw"), None);
    }
}
