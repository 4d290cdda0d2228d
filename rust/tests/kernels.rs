//! Kernel checks: forces are minus the gradient of their potentials; contact law.
use beltrs::forces;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

fn ring(n: usize, wobble: f64) -> Vec<V2> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 3.0 + wobble * ((7 * i) as f64).sin();
            V2::new(r * a.cos() + 0.1 * (i as f64).cos(), 1.7 * r * a.sin())
        })
        .collect()
}

fn axial_energy(x: &[V2], k: &[f64], l0: &[f64]) -> f64 {
    let n = x.len();
    (0..n)
        .map(|e| {
            let d = (x[(e + 1) % n] - x[e]).norm() - l0[e];
            0.5 * k[e] * d * d
        })
        .sum()
}

fn bending_energy(x: &[V2], kt: &[f64]) -> f64 {
    (0..x.len())
        .map(|j| 0.5 * kt[j] * forces::bending_angle(x, j).powi(2))
        .sum()
}

/// Central finite difference of `energy` with respect to node i, component c.
fn gradient(x: &[V2], i: usize, c: usize, energy: &dyn Fn(&[V2]) -> f64) -> f64 {
    let h = 1e-6;
    let mut xp = x.to_vec();
    let mut xm = x.to_vec();
    xp[i][c] += h;
    xm[i][c] -= h;
    (energy(&xp) - energy(&xm)) / (2.0 * h)
}

/// The axial pass also applies the weights (gravity is folded into it) and writes the
/// forces rather than adding to them: the output is minus the gradient of strain plus
/// gravitational energy whatever `f` held before.
#[test]
fn axial_force_is_minus_gradient_of_strain_and_gravity_energy() {
    let x = ring(11, 0.3);
    let n = x.len();
    let k: Vec<f64> = (0..n).map(|e| 1e4 * (1.0 + 0.1 * e as f64)).collect();
    let l0: Vec<f64> = (0..n).map(|e| 1.2 + 0.05 * e as f64).collect();
    let mass: Vec<f64> = (0..n).map(|i| 30.0 + 7.0 * i as f64).collect();
    let g = 9.81;
    let mut f = vec![V2::new(1e9, -3e9); n];
    let mut t = vec![0.0; n];
    forces::axial(&x, &k, &l0, false, &mass, g, &mut t, &mut f);
    let energy = |y: &[V2]| {
        axial_energy(y, &k, &l0) + y.iter().zip(&mass).map(|(p, m)| m * g * p.y).sum::<f64>()
    };
    for i in 0..n {
        for c in 0..2 {
            let grad = gradient(&x, i, c, &energy);
            // Central differences with h = 1e-6 on O(1e4) forces: error ~ h²·E''' ≈ 1e-6 N.
            assert!(
                (f[i][c] + grad).abs() < 1e-4 * (1.0 + grad.abs()),
                "node {i} comp {c}: {} vs {}",
                f[i][c],
                -grad
            );
        }
    }
    for e in 0..n {
        let stretch = (x[(e + 1) % n] - x[e]).norm() - l0[e];
        // The kernel's own expression: equal up to rounding.
        assert!((t[e] - k[e] * stretch).abs() < 1e-9 * k[e], "element {e}");
    }
}

/// Kelvin-Voigt elements: the tension is k(l − l⁰) + c·dl/dt with dl/dt checked by central
/// differences along the node velocities, and each node gets the tensions along its two
/// elements (T·∂l/∂x, by central differences) and its weight. Every node, including the
/// first and last (where the pass closes the loop), is checked.
#[test]
fn damped_axial_force_follows_the_element_tensions() {
    let x = ring(10, 0.25);
    let n = x.len();
    let v: Vec<V2> = (0..n)
        .map(|i| V2::new((1.3 * i as f64).sin(), (0.7 * i as f64).cos()))
        .collect();
    let k: Vec<f64> = (0..n).map(|e| 1e4 * (1.0 + 0.1 * e as f64)).collect();
    let c: Vec<f64> = (0..n).map(|e| 50.0 + 9.0 * e as f64).collect();
    let l0: Vec<f64> = (0..n).map(|e| 1.2 + 0.05 * e as f64).collect();
    let mass: Vec<f64> = (0..n).map(|i| 30.0 + 7.0 * i as f64).collect();
    let g = 9.81;
    let mut f = vec![V2::new(-7e9, 2e9); n];
    let mut t = vec![0.0; n];
    forces::axial_damped(&x, &v, &k, &c, &l0, false, &mass, g, &mut t, &mut f);
    let length = |y: &[V2], e: usize| (y[(e + 1) % n] - y[e]).norm();
    let h = 1e-6;
    let ahead: Vec<V2> = x.iter().zip(&v).map(|(p, w)| p + w * h).collect();
    let behind: Vec<V2> = x.iter().zip(&v).map(|(p, w)| p - w * h).collect();
    for e in 0..n {
        let rate = (length(&ahead, e) - length(&behind, e)) / (2.0 * h);
        let expected = k[e] * (length(&x, e) - l0[e]) + c[e] * rate;
        // Central difference of a length with h = 1e-6: truncation ~ h²·|v|³/l ≈ 1e-12 m/s,
        // rounding ~ 1e-16·l/h ≈ 1e-10 m/s; times c ≈ 1e2 N·s/m: ≤ 1e-7 N.
        assert!(
            (t[e] - expected).abs() < 1e-6,
            "element {e}: {} vs {expected}",
            t[e]
        );
    }
    for i in 0..n {
        for comp in 0..2 {
            let expected: f64 = (0..n)
                .map(|e| -t[e] * gradient(&x, i, comp, &|y: &[V2]| length(y, e)))
                .sum::<f64>()
                - if comp == 1 { mass[i] * g } else { 0.0 };
            // ∂l/∂x by central differences (h = 1e-6): ~1e-10 absolute, on O(1e4) N.
            assert!(
                (f[i][comp] - expected).abs() < 1e-4 * (1.0 + expected.abs()),
                "node {i} comp {comp}: {} vs {expected}",
                f[i][comp]
            );
        }
    }
}

#[test]
fn bending_force_is_minus_gradient_of_bending_energy() {
    let x = ring(9, 0.4);
    let n = x.len();
    let kt: Vec<f64> = (0..n).map(|j| 50.0 + 3.0 * j as f64).collect();
    assert_bending_is_minus_gradient(&x, &kt, V2::zeros(), "ring");
}

/// Run the bending pass on forces that held `initial` and check what it added against the
/// finite-difference gradient of the bending energy (h = 1e-6 central differences on
/// O(100) N forces: 1e-5 relative).
fn assert_bending_is_minus_gradient(x: &[V2], kt: &[f64], initial: V2, what: &str) {
    let n = x.len();
    let mut f = vec![initial; n];
    forces::bending(x, kt, &mut f);
    let energy = |y: &[V2]| bending_energy(y, kt);
    for i in 0..n {
        for c in 0..2 {
            let g = gradient(x, i, c, &energy);
            let added = f[i][c] - initial[c];
            assert!(
                (added + g).abs() < 1e-5 * (1.0 + g.abs()),
                "{what} node {i} comp {c}: {added} vs {}",
                -g
            );
        }
    }
}

/// Bending forces against the energy's finite-difference gradient on a polyline whose kinks
/// range from about 5° to 160°, both signs (a faster kernel that switches from atan(cross/dot)
/// to atan2 at 45° must pass this; see docs/performance.md).
#[test]
fn bending_force_is_minus_gradient_across_small_and_sharp_kinks() {
    let turns = [
        0.09, -0.2, 0.6, 0.78, 0.8, -1.2, 2.8, -0.05, 1.5, -2.2, 0.3, 0.7,
    ];
    // Walk a polyline with these turning angles and varying lengths; close it as a loop (the
    // closing element's two kinks are whatever the geometry makes them).
    let mut x = vec![V2::zeros()];
    let mut heading = 0.0_f64;
    for (i, t) in turns.iter().enumerate() {
        heading += t;
        let l = 1.0 + 0.13 * i as f64;
        let last = *x.last().unwrap();
        x.push(last + V2::new(heading.cos(), heading.sin()) * l);
    }
    let n = x.len();
    let angles: Vec<f64> = (0..n).map(|j| forces::bending_angle(&x, j)).collect();
    assert!(angles.iter().any(|a| a.abs() < 0.2), "{angles:?}");
    assert!(angles.iter().any(|a| a.abs() > 2.0), "{angles:?}");
    let kt: Vec<f64> = (0..n).map(|j| 20.0 + 3.0 * j as f64).collect();
    assert_bending_is_minus_gradient(&x, &kt, V2::zeros(), "polyline");
}

/// The bending pass treats the first, the last two and the middle nodes differently (its
/// sums wrap around the loop): check the smallest loops, where every node is special.
#[test]
fn bending_force_is_minus_gradient_on_the_smallest_loops() {
    for n in 3..=6 {
        let x = ring(n, 0.2);
        let kt: Vec<f64> = (0..n).map(|j| 40.0 + 5.0 * j as f64).collect();
        // Bending adds to what the forces held.
        assert_bending_is_minus_gradient(&x, &kt, V2::new(0.25, -0.5), &format!("n {n}"));
    }
}

/// The axial pass computes its elements in pairs (one SSE2 square root and division for
/// two), the first, the last and an odd one out alone, and reads a uniform belt's
/// parameters as scalars: for odd and even node counts, elastic and damped, with and
/// without clipping, scalars and arrays give the same forces and tensions as a plain
/// element-by-element loop, to the last bit (the same operations in the same order).
#[test]
fn axial_pass_in_pairs_and_with_scalars_matches_a_plain_loop_bit_for_bit() {
    use std::cell::Cell;
    for n in [3, 4, 10, 11] {
        // Rest length the mean element length: some elements slack, some stretched.
        let x = ring(n, 0.6);
        let v: Vec<V2> = (0..n)
            .map(|i| V2::new((i as f64).sin(), 0.3 * (2.0 * i as f64).cos()))
            .collect();
        let l00 = (0..n).map(|e| (x[(e + 1) % n] - x[e]).norm()).sum::<f64>() / n as f64;
        let (k0, c0, m0, g) = (2e4, 35.0, 12.0, 9.81);
        let (k, c, l0, mass) = (vec![k0; n], vec![c0; n], vec![l00; n], vec![m0; n]);
        for damped in [false, true] {
            for tension_only in [false, true] {
                // Reference: element by element, then node by node, in the pass's order.
                let fe_ref: Vec<(f64, V2)> = (0..n)
                    .map(|e| {
                        let j = (e + 1) % n;
                        let d = x[j] - x[e];
                        let l = (d.x * d.x + d.y * d.y).sqrt();
                        let stretch = l - l00;
                        let t = if damped {
                            let dv = v[j] - v[e];
                            k0 * stretch + c0 * ((d.x * dv.x + d.y * dv.y) / l)
                        } else {
                            k0 * stretch
                        };
                        let slack = if damped {
                            stretch < 0.0 || t < 0.0
                        } else {
                            t < 0.0
                        };
                        let t = if tension_only && slack { 0.0 } else { t };
                        (t, d * (t / l))
                    })
                    .collect();
                let f_ref: Vec<V2> = (0..n)
                    .map(|i| {
                        let (cur, prev) = (fe_ref[i].1, fe_ref[(i + n - 1) % n].1);
                        if i == 0 {
                            V2::new((0.0 + cur.x) - prev.x, ((0.0 - m0 * g) + cur.y) - prev.y)
                        } else {
                            V2::new((0.0 - prev.x) + cur.x, ((0.0 - m0 * g) - prev.y) + cur.y)
                        }
                    })
                    .collect();
                assert!(
                    !tension_only || fe_ref.iter().any(|(t, _)| *t == 0.0),
                    "no element was clipped"
                );
                for uniform in [None, forces::Uniform::of(&k, &c, &l0, &mass)] {
                    let belt = forces::AxialBelt {
                        stiffness: &k,
                        damping: &c,
                        rest_length: &l0,
                        mass: &mass,
                        uniform,
                        damped,
                        open: false,
                        tension_only,
                        gravity: g,
                    };
                    let mut f = vec![V2::new(1e9, -3e9); n];
                    let mut t = vec![f64::NAN; n];
                    let nodes = x.iter().zip(&v).map(|(&x, &v)| (x, v));
                    let cells = Cell::from_mut(f.as_mut_slice()).as_slice_of_cells();
                    let _ = forces::axial_pass(&belt, nodes, &mut t.as_mut_slice(), cells);
                    let case = format!(
                        "n {n}, damped {damped}, tension_only {tension_only}, uniform {}",
                        uniform.is_some()
                    );
                    for e in 0..n {
                        assert_eq!(t[e].to_bits(), fe_ref[e].0.to_bits(), "tension {e}, {case}");
                        assert_eq!(
                            f[e].x.to_bits(),
                            f_ref[e].x.to_bits(),
                            "force x {e}, {case}"
                        );
                        assert_eq!(
                            f[e].y.to_bits(),
                            f_ref[e].y.to_bits(),
                            "force y {e}, {case}"
                        );
                    }
                }
            }
        }
    }
}
