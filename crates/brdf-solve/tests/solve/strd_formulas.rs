//! The NIST StRD models whose data files are absent (Bennett5, Lanczos2,
//! MGH17, Nelson, Rat43) against values and gradients computed
//! independently: `tests/fixtures/strd_formulas/formulas.py` writes each
//! formula of `nist_strd/Models` in Python with hand-derived derivatives;
//! `formulas.txt` holds its output. These problems cannot be run against
//! certified values until their files are present, so a wrong formula would
//! otherwise go unnoticed.

use brdf_solve::strd::StrdModel;

fn parse(s: &str) -> Vec<f64> {
    s.split_whitespace().map(|t| t.parse().unwrap()).collect()
}

#[test]
fn formulas_without_data_files_match_the_independent_script() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/strd_formulas/formulas.txt"
    ))
    .unwrap();
    let mut seen = std::collections::BTreeSet::new();
    let mut n = 0;
    for line in text.lines() {
        let parts: Vec<&str> = line.split(';').collect();
        assert_eq!(parts.len(), 4, "fixture line {line}");
        let mut head = parts[0].split_whitespace();
        let name = head.next().unwrap();
        let x: Vec<f64> = head.map(|t| t.parse().unwrap()).collect();
        let (b, f, g) = (parse(parts[1]), parse(parts[2])[0], parse(parts[3]));
        let model = StrdModel::for_problem(name).unwrap_or_else(|| panic!("no model for {name}"));
        assert_eq!(model.n_params(), b.len(), "{name}");
        assert_eq!(model.n_predictors(), x.len(), "{name}");
        assert_eq!(model.log_response(), name == "Nelson", "{name}");
        let mut grad = vec![f64::NAN; b.len()];
        let got = model.eval(&x, &b, &mut grad);
        let tol = |want: f64| 1e-12 * want.abs().max(1e-300) + 1e-300;
        assert!(
            (got - f).abs() <= tol(f),
            "{name} at x {x:?} b {b:?}: {got} vs {f}"
        );
        for (k, (a, w)) in grad.iter().zip(&g).enumerate() {
            assert!(
                (a - w).abs() <= 1e-10 * w.abs() + 1e-300,
                "{name} df/db{} at x {x:?}: {a} vs {w}",
                k + 1
            );
        }
        seen.insert(name.to_string());
        n += 1;
    }
    assert_eq!(n, 30);
    assert_eq!(seen.len(), 5);
}
