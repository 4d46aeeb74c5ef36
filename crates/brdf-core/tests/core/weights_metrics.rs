//! Weights and error metrics against hand-computed values.

use std::f64::consts::{FRAC_PI_2, PI};

use brdf_core::metrics::{lafortune_l2, log_metric, ngan_l2, psnr, relative_rms, rms, sopp_error};
use brdf_core::weights::{MERL_DIMS, cell_edges, grid_solid_angles, merl_bin_solid_angle};

#[test]
fn grid_cells_have_half_edges_and_quarter_corners() {
    // Nodes 0, 1, 2 -> edges 0, 0.5, 1.5, 2: the end cells are half cells.
    assert_eq!(
        cell_edges(&[0.0, 1.0, 2.0]).unwrap(),
        vec![0.0, 0.5, 1.5, 2.0]
    );
    assert!(cell_edges(&[]).is_err());
    assert!(cell_edges(&[1.0, 1.0]).is_err());
}

#[test]
fn grid_solid_angles_sum_to_the_covered_measure() {
    // Sopp's camera grid: theta 0..90 step 2.5 (37), phi 0..180 step 180/35 (36):
    // it covers half the hemisphere, solid angle pi.
    let thetas: Vec<f64> = (0..37).map(|i| (i as f64 * 2.5).to_radians()).collect();
    let phis: Vec<f64> = (0..36).map(|j| j as f64 * PI / 35.0).collect();
    let w = grid_solid_angles(&thetas, &phis).unwrap();
    let s: f64 = w.iter().sum();
    assert!((s - PI).abs() < 1e-12, "{s}");
    // Hand value: the corner cell at theta = 90, phi = 0 spans
    // theta [88.75, 90] deg and phi [0, pi/70]: (cos 88.75 - 0) * pi/70.
    let corner = w[36 * 36];
    let expect = (88.75f64.to_radians().cos()) * PI / 70.0;
    assert!((corner - expect).abs() < 1e-15);
    // An interior cell is twice as wide in phi as an edge cell at the same theta.
    assert!((w[10 * 36 + 5] - 2.0 * w[10 * 36]).abs() < 1e-15);
    // A single azimuth node stands for the whole circle: full hemisphere 2 pi.
    let w1 = grid_solid_angles(&[0.0, FRAC_PI_2], &[0.0]).unwrap();
    assert!((w1.iter().sum::<f64>() - 2.0 * PI).abs() < 1e-12);
}

#[test]
fn merl_bins_sum_to_the_half_diff_measure() {
    let (nh, nd, _np) = MERL_DIMS;
    let mut s = 0.0;
    for ih in 0..nh {
        for id in 0..nd {
            s += merl_bin_solid_angle(ih, id) * 180.0;
        }
    }
    assert!((s - 8.0 * PI * PI).abs() < 1e-9, "{s}");
    // Hand value of bin (0, 0): theta_h in [0, (1/90)^2 pi/2], theta_d in
    // [0, pi/180], phi_d extent 2 pi/180:
    // 8 pi (1 - cos a) (sin^2 b)/2 (2 pi/180).
    let a = (1.0f64 / 90.0).powi(2) * FRAC_PI_2;
    let b = PI / 180.0;
    let expect = 8.0 * PI * (1.0 - a.cos()) * 0.5 * b.sin().powi(2) * (2.0 * PI / 180.0);
    assert!((merl_bin_solid_angle(0, 0) - expect).abs() < 1e-20);
}

#[test]
fn ngan_l2_hand_computed() {
    // Two samples, one channel: cos_i = (1, 0.5), R = (1, 2), M = (0, 0),
    // w = (1, 3): sqrt((1*1 + 3*(0.5*2)^2)/4) = sqrt(4/4) = 1.
    let e = ngan_l2(&[1.0, 2.0], &[0.0, 0.0], &[1.0, 0.5], &[1.0, 3.0]).unwrap();
    assert!((e.total - 1.0).abs() < 1e-15);
    // Two channels: second channel error 0 -> total sqrt((1 + 0)/2).
    let e = ngan_l2(
        &[1.0, 2.0, 5.0, 5.0],
        &[0.0, 0.0, 5.0, 5.0],
        &[1.0, 0.5],
        &[1.0, 3.0],
    )
    .unwrap();
    assert_eq!(e.per_channel.len(), 2);
    assert!((e.per_channel[1]).abs() < 1e-15);
    assert!((e.total - 0.5f64.sqrt()).abs() < 1e-15);
    assert!(ngan_l2(&[], &[], &[], &[]).is_err());
    assert!(ngan_l2(&[1.0], &[1.0, 2.0], &[1.0], &[1.0]).is_err());
    assert!(ngan_l2(&[1.0], &[1.0], &[1.0], &[0.0]).is_err());
}

#[test]
fn lafortune_log_and_sopp_hand_computed() {
    // Lafortune: cos_i cos_o = 0.5 * 0.5, R - M = 4 -> |1| on one sample.
    let e = lafortune_l2(&[4.0], &[0.0], &[0.5], &[0.5], &[1.0]).unwrap();
    assert!((e.total - 1.0).abs() < 1e-15);
    // Log: ln(1 + (e - 1)) - ln(1 + 0) = 1.
    let e = log_metric(&[std::f64::consts::E - 1.0], &[0.0], &[1.0], &[1.0]).unwrap();
    assert!((e.total - 1.0).abs() < 1e-15);
    // Sopp unweighted: r = cos_i (R - M) / n = (1*2/2, 0.5*4/2) = (1, 1):
    // sqrt(2). Weighted with w = (1, 3): r = (1*1*2/4, 3*0.5*4/4) = (0.5, 1.5).
    let u = sopp_error(&[2.0, 4.0], &[0.0, 0.0], &[1.0, 0.5], &[1.0, 3.0], false).unwrap();
    assert!((u.total - 2f64.sqrt()).abs() < 1e-15);
    let w = sopp_error(&[2.0, 4.0], &[0.0, 0.0], &[1.0, 0.5], &[1.0, 3.0], true).unwrap();
    assert!((w.total - (0.25f64 + 2.25).sqrt()).abs() < 1e-15);
}

#[test]
fn rms_relative_rms_psnr_hand_computed() {
    assert!((rms(&[1.0, 3.0], &[0.0, 0.0]).unwrap() - 5f64.sqrt()).abs() < 1e-15);
    assert!((relative_rms(&[1.0, 1.0], &[2.0, 2.0]).unwrap() - 0.5).abs() < 1e-15);
    assert_eq!(relative_rms(&[0.0], &[0.0]).unwrap(), 0.0);
    // MSE 0.01 with peak 1 -> 20 dB.
    let p = psnr(&[0.1, 0.1], &[0.0, 0.2], 1.0).unwrap();
    assert!((p - 20.0).abs() < 1e-12);
    assert_eq!(psnr(&[0.5], &[0.5], 1.0).unwrap(), f64::INFINITY);
    assert!(psnr(&[0.5], &[0.5], 0.0).is_err());
    assert!(rms(&[1.0], &[]).is_err());
}
