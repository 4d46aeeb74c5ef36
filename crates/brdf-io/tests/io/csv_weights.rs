//! A sample CSV without a `weight` column is read with unit weights and a
//! note saying so; a file with the column reads exactly as before (its
//! weights, no note).

use std::path::Path;

use brdf_io::csv_samples::parse;

const ROWS: [[f64; 6]; 3] = [
    [0.1, 0.0, 0.2, 3.0, 0.5, 0.25],
    [0.7, 1.5, 0.3, -2.0, 0.125, 2.0],
    [1.2, -3.0, 0.9, 6.2, 1.75, 0.5],
];

fn text(weighted: bool) -> String {
    let mut t = String::from("theta_i,phi_i,theta_o,phi_o,grey");
    if weighted {
        t += ",weight";
    }
    t += "\n";
    for r in ROWS {
        let k = if weighted { 6 } else { 5 };
        let cells: Vec<String> = r[..k].iter().map(|x| x.to_string()).collect();
        t += &cells.join(",");
        t += "\n";
    }
    t
}

/// The incident direction's z is cos(theta_i), computed here directly.
fn check_directions(set: &brdf_core::SampleSet) {
    let p = set.pairs();
    for (j, r) in ROWS.iter().enumerate() {
        assert!((p.l(j)[2] - r[0].cos()).abs() < 1e-15, "row {j}");
        assert!((p.v(j)[2] - r[2].cos()).abs() < 1e-15, "row {j}");
    }
}

#[test]
fn without_a_weight_column_every_sample_weighs_one_and_a_note_says_so() {
    let set = parse(Path::new("dir/data.csv"), &text(false)).expect("reads");
    assert_eq!(set.len(), 3);
    assert_eq!(set.channel_names, ["grey"]);
    assert_eq!(set.weights(), [1.0, 1.0, 1.0]);
    assert_eq!(set.channel(0), [0.5, 0.125, 1.75]);
    check_directions(&set);
    assert_eq!(
        set.notes,
        ["dir/data.csv: no weight column; every sample weighted 1"]
    );
}

#[test]
fn with_a_weight_column_the_weights_are_read_and_nothing_is_noted() {
    let set = parse(Path::new("data.csv"), &text(true)).expect("reads");
    assert_eq!(set.weights(), [0.25, 2.0, 0.5]);
    assert_eq!(set.channel(0), [0.5, 0.125, 1.75]);
    check_directions(&set);
    assert!(set.notes.is_empty(), "{:?}", set.notes);
}

#[test]
fn rgb_without_weights_keeps_three_channels() {
    let t = "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,r,g,b\n10,0,20,180,0.1,0.2,0.3\n";
    let set = parse(Path::new("rgb.csv"), t).expect("reads");
    assert_eq!(set.channel_names, ["r", "g", "b"]);
    assert_eq!(set.weights(), [1.0]);
    assert_eq!(
        [set.channel(0)[0], set.channel(1)[0], set.channel(2)[0]],
        [0.1, 0.2, 0.3]
    );
    assert_eq!(set.notes.len(), 1);
}

#[test]
fn a_header_without_any_channel_is_still_refused() {
    let e = parse(
        Path::new("x.csv"),
        "theta_i,phi_i,theta_o,phi_o,weight\n0,0,0,0,1\n",
    )
    .expect_err("no channel");
    assert!(e.to_string().starts_with("x.csv:1: header must be"), "{e}");
    let e = parse(Path::new("x.csv"), "theta_i,phi_i,theta_o,phi_o\n0,0,0,0\n")
        .expect_err("no channel");
    assert!(e.to_string().contains("header must be"), "{e}");
}

#[test]
fn a_missing_value_in_a_row_is_still_counted_against_the_header() {
    let e = parse(
        Path::new("x.csv"),
        "theta_i,phi_i,theta_o,phi_o,grey\n0,0,0,0\n",
    )
    .expect_err("short row");
    assert!(e.to_string().contains("x.csv:2"), "{e}");
}
