//! A finished study's table summed up per layout: runs, how many linked
//! and at which steps, what the first links join, how many converged at
//! every step, and the outcomes (the held-out pairs' table of
//! `docs/fracture-model.md`, *Coalescence*; a study without a
//! `flaws.layout` axis is one group, `all`).

use super::flaws::Layout;
use super::row::Table;

/// Header lines of [`by_layout`]'s Markdown table.
pub const HEADER: &str = "| layout | runs | linked (first link at) | what the first link joins | every step converged | outcomes |\n\
                          | --- | --- | --- | --- | --- | --- |\n";

/// One Markdown row per layout, in the order of [`Layout::ALL`] (each
/// row's key, `1-coplanar`, sorts in that order).
pub fn by_layout(table: &Table) -> Vec<(String, String)> {
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
        .iter()
        .enumerate()
        .map(|(k, (_, label, rows))| {
            let key = format!("{}-{}", k + 1, label.replace(", ", "-").replace(' ', "-"));
            (key, row(table, label, rows))
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
    let joins = counted(rows.iter().map(|&r| cell(r, "link_joins")));
    let converged = rows
        .iter()
        .filter(|&&r| cell(r, "every_step_converged") == "true")
        .count();
    let outcomes = counted(rows.iter().map(|&r| cell(r, "outcome")));
    format!(
        "| {label} | {} | {linked} | {} | {converged} | {} |\n",
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Three rows of two layouts: the groups in the layouts' order, their
    /// links' steps as a span, the joins and outcomes most first.
    #[test]
    fn rows_are_summed_up_per_layout_in_order() {
        let text = "point,flaws.layout,outcome,every_step_converged,link_step,link_joins\n\
                    1,stepped,through,true,5,wing–wing\n\
                    2,overlapping_mirrored,through,false,,\n\
                    3,stepped,max_steps,true,43,secondary–wing\n\
                    4,stepped,through,true,12,wing–wing\n";
        let table = Table::parse(text).expect("parses");
        let rows = by_layout(&table);
        assert_eq!(
            rows,
            [
                (
                    "1-stepped".to_owned(),
                    "| stepped | 3 | 3 (steps 5–43) | 2 wing–wing, 1 secondary–wing | 3 | 2 through, 1 max_steps |\n"
                        .to_owned()
                ),
                (
                    "2-overlapping-mirrored".to_owned(),
                    "| overlapping, mirrored | 1 | 0 | – | 0 | 1 through |\n".to_owned()
                ),
            ]
        );
    }
}
