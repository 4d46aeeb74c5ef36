//! The appearance fit through the command: `brdf fit` on data
//! that can be rendered reports image errors and its candidates, scattered
//! data say why there are none, and `brdf select --by-image` ranks renderer
//! models by their image error.

use brdf_fit::judged::COLOUR_PLANE_NOTE;

use crate::common;
use common::{brdf, data_file};

#[test]
#[ignore = "needs BRDF_DATA"]
fn fit_of_a_renderer_model_reports_image_errors_and_candidates() {
    let p = data_file("rgl/paper_white_rgb.bsdf");
    let p = p.display().to_string();
    let (ok, out, err) = brdf(&["fit", "--data", &p, "--model", "gltf", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let lights = v["image_errors"][0]["lights"]
        .as_array()
        .expect("image errors");
    assert_eq!(lights.len(), 2);
    for l in lights {
        let flip = l["flip"].as_f64().expect("flip");
        // A white paper is close to Lambertian: its fit renders alike.
        assert!(flip > 0.0 && flip < 0.15, "{l}");
        assert!(l["delta_e"].as_f64().expect("dE") < 3.0, "{l}");
    }
    let candidates = v["candidates"][0].as_array().expect("candidates");
    assert_eq!(candidates.iter().filter(|c| c["chosen"] == true).count(), 1);
    assert!(
        candidates.len() >= 4,
        "two objectives, the lobes and the image refinement"
    );
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn a_film_keeps_its_colour_and_a_lobe_only_when_the_render_pays() {
    // vch_golden_yellow, principled, the default appearance fit. Before
    // the mean-colour rows of the image objective the fit's mean colour was
    // CIEDE2000 5.2 (sky) from the data's; the rows bring it under 3. The
    // rough clear coat is switched on only in the image objective, where it
    // lowers the mean FLIP by more than the 5% margin.
    let v = fit_json("rgl/vch_golden_yellow_rgb.bsdf", "principled");
    for l in v["image_errors"][0]["lights"].as_array().expect("lights") {
        assert!(l["delta_e"].as_f64().expect("dE") < 3.0, "{l}");
    }
    // Its colours keep close to one plane of white and a yellow: no note.
    let plane = &v["image_errors"][0]["colour_plane"];
    assert!(
        plane["outside"].as_f64().expect("outside") < COLOUR_PLANE_NOTE,
        "{plane}"
    );
    assert!(
        !v["notes"].to_string().contains("plane of white"),
        "{}",
        v["notes"]
    );
    let (all, chosen) = candidates(&v);
    assert_eq!(chosen["objective"], "image", "{chosen}");
    assert_eq!(
        chosen["lobes"],
        serde_json::json!(["clearcoat"]),
        "{chosen}"
    );
    let best_without = all
        .iter()
        .filter(|c| lobes(c) == 0)
        .map(candidate_flip)
        .fold(f64::INFINITY, f64::min);
    assert!(
        candidate_flip(chosen) < 0.95 * best_without,
        "{chosen} against {best_without}"
    );
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn scattered_data_say_no_image_error_can_be_formed() {
    let p = data_file("curet/abrdf.dat");
    let spec = format!("{}#25", p.display());
    let fit = |extra: &[&str]| {
        let mut args = vec![
            "fit",
            "--data",
            &spec,
            "--model",
            "ggx",
            "--channels",
            "grey",
        ];
        args.extend_from_slice(extra);
        brdf(&args)
    };
    let (ok, out, err) = fit(&[]);
    assert!(ok, "{err}");
    assert!(out.contains("no image error"), "{out}");
    // Nor can a fit of them be polished on its render.
    let (ok, _, err) = fit(&["--polish"]);
    assert!(!ok);
    assert!(
        err.contains("--polish") && err.contains("RGL") && err.lines().count() == 1,
        "{err}"
    );
    let (ok, _, err) = brdf(&["select", "--data", &spec, "--by-image"]);
    assert!(!ok);
    assert!(
        err.contains("--by-image") && err.contains("scattered"),
        "{err}"
    );
}

/// `brdf select --data P --by-image --models MODELS --json` plus `extra`.
fn select_by_image(p: &str, models: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "select",
        "--data",
        p,
        "--by-image",
        "--models",
        models,
        "--json",
    ];
    args.extend_from_slice(extra);
    let (ok, out, err) = brdf(&args);
    assert!(ok, "{err}");
    serde_json::from_str(&out).expect("json")
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn select_by_image_marks_the_least_flip() {
    let p = data_file("rgl/paper_white_rgb.bsdf");
    let v = select_by_image(&p.display().to_string(), "gltf,ggx", &[]);
    let rows = v["candidates"].as_array().expect("rows");
    assert_eq!(rows.len(), 2);
    let mean = |r: &serde_json::Value| {
        let l = r["image"]["lights"].as_array().expect("lights");
        l.iter()
            .map(|x| x["flip"].as_f64().expect("flip"))
            .sum::<f64>()
            / l.len() as f64
    };
    let best = rows.iter().map(mean).fold(f64::INFINITY, f64::min);
    assert_eq!(mean(&v["choice"]), best);
}

/// Mean HDR-FLIP over the light sets of a `brdf fit --json` report.
fn mean_flip(v: &serde_json::Value) -> f64 {
    let lights = v["image_errors"][0]["lights"]
        .as_array()
        .expect("image errors");
    lights
        .iter()
        .map(|l| l["flip"].as_f64().expect("flip"))
        .sum::<f64>()
        / lights.len() as f64
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn the_image_objective_alone_refines_the_ngan_fit_for_its_render() {
    // `--metric image` was listed but failed on data that can be rendered
    // ("needs data that can be evaluated at any direction pair"): the
    // objective had no target. It now starts from the Ngan fit, so its
    // render is at least as close to the data's as that fit's.
    let p = data_file("rgl/paper_white_rgb.bsdf");
    let p = p.display().to_string();
    let fit = |metric: &str| {
        let (ok, out, err) = brdf(&[
            "fit", "--data", &p, "--model", "ggx", "--metric", metric, "--json", "--quiet",
        ]);
        assert!(ok, "--metric {metric}: {err}");
        serde_json::from_str::<serde_json::Value>(&out).expect("json")
    };
    let (image, ngan) = (fit("image"), fit("ngan"));
    assert_eq!(image["fits"][0]["objective"], "image");
    assert!(
        image["candidates"][0]
            .as_array()
            .is_none_or(|c| c.is_empty())
    );
    let (fi, fn_) = (mean_flip(&image), mean_flip(&ngan));
    assert!(
        fi < fn_,
        "image objective {fi} against its Ngan start {fn_}"
    );
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn lobes_that_pay_only_together_are_tried_together() {
    // paper_white, principled: sheen alone or clear coat alone under the
    // winning objective do not render the paper as well as the Ngan fit
    // with both on, which the single-lobe trials could not reach (they are
    // nested under the winning objective, cube-root). The pair must win by
    // the lobe margin over every candidate with fewer lobes.
    let v = fit_json("rgl/paper_white_rgb.bsdf", "principled");
    let (all, chosen) = candidates(&v);
    assert_eq!(
        chosen["lobes"],
        serde_json::json!(["sheen", "clearcoat"]),
        "{chosen}"
    );
    let fewer = || {
        all.iter()
            .filter(|c| c["objective"] != "image" && lobes(c) < 2)
    };
    let best_fewer = fewer().map(candidate_flip).fold(f64::INFINITY, f64::min);
    assert!(
        candidate_flip(chosen) < 0.95 * best_fewer,
        "{chosen} against {best_fewer}"
    );
    // The fit keeps the body of the data: no worse in Ngan's L2 than the
    // best candidate with fewer lobes.
    let l2 = |c: &serde_json::Value| c["ngan_l2"].as_f64().expect("l2");
    let l2_fewer = fewer().map(l2).fold(f64::INFINITY, f64::min);
    assert!(l2(chosen) <= l2_fewer, "{chosen} against {l2_fewer}");
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn select_reports_the_image_errors_of_its_choice() {
    // `brdf select --by-l2` on data that can be rendered carries
    // the chosen fit's image errors, the same as `brdf fit` of that model
    // (koenderink order 6 on paper_white: a direct solve, so the same
    // fit); on scattered data the note why there are none.
    let (p, curet) = (
        data_file("rgl/paper_white_rgb.bsdf"),
        data_file("curet/abrdf.dat"),
    );
    let p = p.display().to_string();
    let (ok, out, err) = brdf(&["select", "--data", &p, "--by-l2", "--json", "--quiet"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert_eq!(
        v["choice"]["label"], "koenderink order 6",
        "{}",
        v["choice"]
    );
    let (ok, out, err) = brdf(&[
        "fit",
        "--data",
        &p,
        "--model",
        "koenderink",
        "--order",
        "6",
        "--json",
        "--quiet",
    ]);
    assert!(ok, "{err}");
    let fit: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert_eq!(v["choice"]["error"], fit["fits"][0]["ngan_l2"]);
    assert_eq!(v["choice_image_error"], fit["image_errors"][0]);
    let (ok, out, err) = brdf(&["select", "--data", &p, "--by-l2", "--quiet"]);
    assert!(ok, "{err}");
    assert!(
        out.contains("The choice, koenderink order 6:\nimage error (sky, 128 px): FLIP"),
        "{out}"
    );
    let spec = format!("{}#25", curet.display());
    let (ok, out, err) = brdf(&["select", "--data", &spec, "--json", "--quiet"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert!(v["choice_image_error"].is_null());
    assert!(
        v["image_note"]
            .as_str()
            .is_some_and(|n| n.contains("no image error")),
        "{v}"
    );
}

/// `brdf fit --data FILE --model MODEL --json` of a shared RGL file.
fn fit_json(file: &str, model: &str) -> serde_json::Value {
    let p = data_file(file).display().to_string();
    let (ok, out, err) = brdf(&["fit", "--data", &p, "--model", model, "--json"]);
    assert!(ok, "{err}");
    serde_json::from_str(&out).expect("json")
}

/// Mean HDR-FLIP over the light sets of a candidate.
fn candidate_flip(c: &serde_json::Value) -> f64 {
    let l = c["image"]["lights"].as_array().expect("lights");
    l.iter()
        .map(|l| l["flip"].as_f64().expect("flip"))
        .sum::<f64>()
        / l.len() as f64
}

/// Number of optional lobes a candidate has on.
fn lobes(c: &serde_json::Value) -> usize {
    c["lobes"].as_array().expect("lobes").len()
}

/// The candidates of the first fit of a report, and the chosen one.
fn candidates(v: &serde_json::Value) -> (&Vec<serde_json::Value>, &serde_json::Value) {
    let all = v["candidates"][0].as_array().expect("candidates");
    let chosen = all.iter().find(|c| c["chosen"] == true).expect("chosen");
    (all, chosen)
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn polish_lowers_the_image_error_and_keeps_the_colour() {
    // cc_iris_purple_gem, principled: `--polish` ends the default fit
    // with a compass search on the mean FLIP of brdf-render's renders.
    // Its start is the default fit's choice, so its candidate, when
    // chosen, renders with less mean FLIP than every other candidate at
    // 32 px, and the report's 128-px mean FLIP is lower than the default
    // fit's; the mean colour may drift only to a just-noticeable
    // difference (CIEDE2000 2.3) or the start's.
    let p = data_file("rgl/cc_iris_purple_gem_rgb.bsdf");
    let p = p.display().to_string();
    let run = |extra: &[&str]| {
        let mut args = vec!["fit", "--data", &p, "--model", "principled", "--json"];
        args.extend_from_slice(extra);
        let (ok, out, err) = brdf(&args);
        assert!(ok, "{err}");
        serde_json::from_str::<serde_json::Value>(&out).expect("json")
    };
    let (plain, polished) = (run(&[]), run(&["--polish"]));
    // The film's highlight and rim are other hues than its blue body: its
    // colours lie off every plane of white and one colour, and the report
    // says no principled fit can match them.
    let plane = &plain["image_errors"][0]["colour_plane"];
    assert_eq!(plane["light"], "studio", "{plane}");
    assert!(
        plane["outside"].as_f64().expect("outside") > COLOUR_PLANE_NOTE,
        "{plane}"
    );
    let notes = plain["notes"][0].as_array().expect("notes");
    assert!(
        notes.iter().any(|n| n
            .as_str()
            .is_some_and(|n| n.contains("every plane of white and one colour"))),
        "{notes:?}"
    );
    let (all, chosen) = candidates(&polished);
    assert_eq!(chosen["objective"], "flip", "{chosen}");
    let (plain_all, plain_chosen) = candidates(&plain);
    assert_eq!(all.len(), plain_all.len() + 1);
    for c in plain_all {
        assert!(candidate_flip(chosen) < candidate_flip(c), "{c}");
    }
    let report_flip = |v: &serde_json::Value| mean_flip(v);
    assert!(report_flip(&polished) < report_flip(&plain));
    let max_de = |c: &serde_json::Value| {
        c["image"]["lights"]
            .as_array()
            .expect("lights")
            .iter()
            .map(|l| l["delta_e"].as_f64().expect("dE"))
            .fold(0.0, f64::max)
    };
    assert!(max_de(chosen) <= max_de(plain_chosen).max(2.3) + 1e-9);
    let solver = polished["fits"][0]["solver"].as_str().unwrap_or_default();
    assert!(solver.contains("compass search"), "{solver}");
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn gltf_with_khr_extensions_fits_a_measured_paint_for_appearance() {
    // colodur_napoli, gltf-ext, the default appearance fit. Holding the
    // clear coat's roughness (box (0, 1], open below) while the coat is
    // off once made an empty box, and every gltf-ext appearance fit
    // failed; the workspace tests, all synthetic, did not see it.
    let v = fit_json("rgl/colodur_napoli_4f_rgb.bsdf", "gltf-ext");
    for l in v["image_errors"][0]["lights"].as_array().expect("lights") {
        // A matte wall paint: its fit renders alike (Mitsuba: 0.076 / 0.068).
        assert!(l["flip"].as_f64().expect("flip") < 0.15, "{l}");
    }
    let params = v["fits"][0]["parameters"].as_array().expect("parameters");
    let value = |name: &str| {
        params
            .iter()
            .find(|p| p["name"] == name)
            .and_then(|p| p["value"].as_f64())
            .expect(name)
    };
    if value("clearcoat") == 0.0 {
        assert_eq!(value("clearcoat_roughness"), 0.1);
    }
    let (_, chosen) = candidates(&v);
    assert!(chosen["objective"].is_string());
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn select_by_image_polishes_as_fit_does() {
    // `brdf select --by-image --polish`: each model's row is the fit that
    // `brdf fit --polish` makes, the same image errors; without --by-image
    // the flag is refused with the way to use it.
    let p = data_file("rgl/paper_white_rgb.bsdf");
    let p = p.display().to_string();
    let v = select_by_image(&p, "ggx", &["--polish"]);
    let (ok, fit, err) = brdf(&[
        "fit", "--data", &p, "--model", "ggx", "--polish", "--json", "--quiet",
    ]);
    assert!(ok, "{err}");
    let fit: serde_json::Value = serde_json::from_str(&fit).expect("json");
    assert_eq!(v["choice"]["image"], fit["image_errors"][0]);
    let (ok, _, err) = brdf(&["select", "--data", &p, "--by-l2", "--polish"]);
    assert!(!ok);
    assert!(err.contains("--by-image"), "{err}");
}
