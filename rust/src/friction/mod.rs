//! Stick-force friction (Taylor & Preece 1989, extended by Hustrulid to external forces and
//! multiple contacts: thesis eq. 4.76–4.94 and figure 4.9).
//!
//! The stick force is the tangential force that brings the contact to zero relative
//! tangential speed by the end of the step. It is applied if it stays within µs·N;
//! otherwise the node slips with µk·N in the same direction, its force becomes a known
//! torque on the pulley, and the remaining nodes are solved again. Because the applied force
//! never exceeds the stick force, friction can stop a slip but never reverse it: there is
//! no oscillation about zero relative speed.
//!
//! µs·N is the limit of a contact at rest. A contact that slid in the last step, or whose
//! neighbour on the pulley did (the slip front), has µk·N instead (Coulomb's kinetic state;
//! `static_limits`, the memory in `State::sliding`): a slip arc then slides steadily at
//! µk as in creep theory, instead of sticking to µs·N and breaking away node by node.

pub mod creep;
pub mod stage;

use crate::contact::{IdlerContact, PulleyContacts};
use crate::forces::perp;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Scratch per pulley for the friction solve; reused every step.
#[derive(Debug, Clone, Default)]
pub struct StickScratch {
    /// m_i·v_n,i/Δt + t_i·F_i for each contact (the stick force if the pulley did not move).
    free: Vec<f64>,
    /// Whether each contact is still sticking.
    sticking: Vec<bool>,
    /// Tangential friction force of each contact (positive along t_i on the pulley), N.
    pub force: Vec<f64>,
    /// Storage of the slip loop's two sorted candidate lists (see `release_slipping`).
    list_pos: Vec<u128>,
    list_neg: Vec<u128>,
    /// Each contact's excess over its static limit per unit mass at α = 0, "+" and "−"
    /// sides, m/s².
    key_pos: Vec<f64>,
    key_neg: Vec<f64>,
    /// Each contact's static limit, N: µs·N at rest, µk·N while sliding or next to a
    /// sliding contact (see [`static_limits`]).
    limit: Vec<f64>,
    /// Whether each contact slid in the previous step.
    slid: Vec<bool>,
    /// The belt points that slid on this pulley in the previous step (input; the state's
    /// friction memory, `State::sliding`), replaced by those that slide in this step
    /// (output), in ascending order. Empty: every contact at rest before the step.
    pub sliding: Vec<usize>,
}

/// Prescribed motion of a pulley with a limited torque: whatever holds the pulley (a brake
/// that stops it, a speed-controlled drive that makes it follow a starting curve, a
/// holdback that stops it turning backwards) supplies the torque that gives the pulley the
/// prescribed speed at the end of the step, if that torque lies within its range;
/// otherwise it supplies the nearest end of the range and the pulley moves freely under it.
/// A two-sided range ±capacity is a brake or a drive; a one-sided one (e.g. [0, capacity])
/// is a holder that can act one way only (a holdback, a brake that must not drive).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prescribed {
    /// Angular speed the pulley is to have at t + Δt/2, rad/s.
    pub omega: f64,
    /// Smallest torque the holder can supply, N·m, ≤ `max_torque` (may be −∞).
    pub min_torque: f64,
    /// Largest torque the holder can supply, N·m (may be +∞).
    pub max_torque: f64,
}

impl Prescribed {
    /// A brake of this capacity (N·m) holding the pulley at rest.
    pub fn at_rest(capacity: f64) -> Prescribed {
        Prescribed::within(0.0, capacity)
    }

    /// Speed `omega` (rad/s) with a torque of at most `capacity` (N·m, ≥ 0) either way.
    pub fn within(omega: f64, capacity: f64) -> Prescribed {
        Prescribed {
            omega,
            min_torque: -capacity,
            max_torque: capacity,
        }
    }

    /// Angular acceleration (rad/s²) that takes the pulley from `omega` (at t − Δt/2) to
    /// the prescribed speed in one step `dt`; 0 for an infinite step (quasi-static).
    #[inline]
    pub fn alpha(&self, omega: f64, dt: f64) -> f64 {
        if dt.is_finite() {
            (self.omega - omega) / dt
        } else {
            0.0
        }
    }

    /// The holder's torque when `needed` (N·m) is the torque that gives the prescribed
    /// motion: (`needed`, true) if within the range, else (the nearest end of the range,
    /// false).
    #[inline]
    pub fn limit(&self, needed: f64) -> (f64, bool) {
        if needed < self.min_torque {
            (self.min_torque, false)
        } else if needed > self.max_torque {
            (self.max_torque, false)
        } else {
            (needed, true)
        }
    }
}

/// The pulley seen by the friction solve.
#[derive(Debug, Clone, Copy)]
pub struct FrictionPulley {
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia, kg·m².
    pub inertia: f64,
    /// Angular speed at t − Δt/2, rad/s.
    pub omega: f64,
    /// Centre velocity, m/s.
    pub center_velocity: V2,
    /// Torque from everything but belt friction (drive), N·m.
    pub applied_torque: f64,
    /// Static and kinetic coefficients.
    pub mu_static: f64,
    /// Kinetic coefficient.
    pub mu_kinetic: f64,
    /// Prescribed motion (a brake or a speed-controlled drive), solved with the friction:
    /// the holder either holds the pulley to the prescribed speed this step or supplies its
    /// capacity. `None`: the pulley is free.
    pub prescribed: Option<Prescribed>,
}

/// Result of one pulley's friction solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FrictionOutcome {
    /// Torque of belt friction on the pulley, N·m (counter-clockwise positive).
    pub torque: f64,
    /// Resultant friction force on the pulley, N.
    pub force: V2,
    /// Sum of the tangential friction forces, N.
    pub tangential: f64,
    /// Number of slipping nodes.
    pub slipping: usize,
    /// Torque of the holder (brake or speed-controlled drive), N·m, when the pulley's
    /// motion is prescribed (solved with the friction).
    pub held_torque: Option<f64>,
    /// The holder holds the pulley: it reaches the prescribed speed this step (exactly, not
    /// up to rounding).
    pub holds: bool,
}

/// Solve and apply stick-force friction for the nodes touching one pulley
/// (thesis eq. 4.91 with the slip loop of figure 4.9).
///
/// With t_i the counter-clockwise tangent at node i, v_n,i = t_i·(v_i − v_p) − Rω the
/// relative speed, F_i all other forces on the node, and the sticking set S:
/// f_i = m_i v_n,i/Δt + t_i·F_i − m_i R (T + R·A)/(I + R² M), where A and M sum
/// m_j v_n,j/Δt + t_j·F_j and m_j over S and T is the applied torque plus the torque of the
/// slipping nodes. The node receives −f_i t_i, the pulley +f_i t_i and torque R f_i.
/// Rigid bodies resting on their ends have their own arms ([`PulleyContacts::lever`] for the
/// surface's speed under the body, [`PulleyContacts::arm`] for the friction's moment), which
/// take R's place contact by contact (see `release_slipping_arms`).
/// A prescribed motion (brake, speed-controlled drive) is solved here too (see
/// [`FrictionPulley::prescribed`]).
#[allow(clippy::too_many_arguments)]
pub fn pulley_stick_friction(
    contacts: &PulleyContacts,
    pulley: &FrictionPulley,
    v: &[V2],
    mass: &[f64],
    dt: f64,
    force: &mut [V2],
    scratch: &mut StickScratch,
) -> FrictionOutcome {
    let nc = contacts.len();
    scratch.free.clear();
    scratch.sticking.clear();
    scratch.force.clear();
    let r = pulley.radius;
    for k in 0..nc {
        let i = contacts.node[k];
        let t = perp(contacts.normal[k]);
        let lever = contacts.lever_at(k, r);
        let vn = t.dot(&(v[i] - pulley.center_velocity)) - lever * pulley.omega;
        scratch.free.push(mass[i] * vn / dt + t.dot(&force[i]));
        scratch.sticking.push(true);
        scratch.force.push(0.0);
    }
    static_limits(contacts, pulley, v.len(), dt, scratch);
    // A holder (brake, speed-controlled drive) that can hold the pulley fixes its motion:
    // it reaches the prescribed speed this step (a brake stops it). The nodes then stick to
    // (or slip on) a pulley of prescribed motion, one by one, and the holder takes what the
    // belt and the other torques leave. If that exceeds its capacity it supplies the
    // capacity (a brake slides, opposing the motion or the tendency to move; a drive is at
    // its torque limit), a known torque below.
    let mut held = None;
    if let Some(prescribed) = pulley.prescribed {
        let alpha = prescribed.alpha(pulley.omega, dt);
        let mut tangential = 0.0;
        let mut slipped = 0;
        // Per-contact arms (rigid bodies): the surface's acceleration at contact k is
        // lever_k·α and its friction's moment arm_k·f_k; nodes: the radius for both.
        let arms = !contacts.arm.is_empty();
        let mut moment = 0.0;
        for k in 0..nc {
            let m = mass[contacts.node[k]];
            let stick = if arms {
                scratch.free[k] - m * (contacts.lever_at(k, r) * alpha)
            } else {
                scratch.free[k] - m * r * alpha
            };
            let (f, slips) = limit(stick, scratch.limit[k], contacts.normal_force[k], pulley);
            scratch.force[k] = f;
            scratch.sticking[k] = !slips;
            slipped += usize::from(slips);
            tangential += f;
            if arms {
                moment += contacts.arm_at(k, r) * f;
            }
        }
        let belt_torque = if arms { moment } else { r * tangential };
        let needed = pulley.inertia * alpha - pulley.applied_torque - belt_torque;
        let (torque, holds) = prescribed.limit(needed);
        if holds {
            let mut out = apply(
                contacts,
                scratch,
                force,
                (r, dt.is_finite()),
                slipped,
                Some(torque),
            );
            out.holds = true;
            return out;
        }
        held = Some(torque);
        scratch.sticking.iter_mut().for_each(|s| *s = true);
    }
    let known_torque = pulley.applied_torque + held.unwrap_or(0.0);
    let slipping = if contacts.arm.is_empty() {
        release_slipping(contacts, pulley, mass, scratch, known_torque)
    } else {
        release_slipping_arms(contacts, pulley, mass, scratch, known_torque)
    };
    apply(
        contacts,
        scratch,
        force,
        (r, dt.is_finite()),
        slipping,
        held,
    )
}

/// A slip candidate as one integer that sorts worst first: the excess per unit mass at
/// α = 0 on one side (`key`, larger is worse) in the high 64 bits, mapped to an unsigned
/// order and inverted, then the contact index (lower first on equal keys, as the
/// one-at-a-time scan chose) in the low 64 bits.
#[inline]
fn sort_key(key: f64, index: usize) -> u128 {
    let bits = key.to_bits();
    // IEEE order as unsigned: flip all bits of negatives, the sign bit of the others.
    let ordered = if bits >> 63 == 1 {
        !bits
    } else {
        bits | (1 << 63)
    };
    (u128::from(!ordered) << 64) | index as u128
}

/// The contacts `k` with `include[k]`, as [`sort_key`]s of `key[k]` in ascending order
/// (worst first), into `out`. Integer keys: a float comparator sorts several times slower.
fn sort_worst_first(key: &[f64], include: &[bool], out: &mut Vec<u128>) {
    out.clear();
    for (k, (&x, &inc)) in key.iter().zip(include).enumerate() {
        if inc {
            out.push(sort_key(x, k));
        }
    }
    out.sort_unstable();
}

/// The slip loop of thesis figure 4.9 for a pulley that moves freely under `known_torque`
/// (N·m, everything but belt friction): release the worst violator of the static limit,
/// re-solve the pulley's angular acceleration α with its kinetic force known, repeat until
/// every sticking node is within µs·N. Returns the number of slipping nodes; the forces are
/// left in `scratch.force`.
///
/// A sticking node's stick force is f_k = free_k − m_k·r·α, so its excess over the static
/// limit per unit node mass is A_k − r·α on the "+" side (f > 0) and B_k + r·α on the "−"
/// side, with A_k = (free_k − µs·N_k)/m_k and B_k = (−free_k − µs·N_k)/m_k fixed for the
/// step. The order of the candidates on each side therefore does not depend on α: the two
/// lists sorted by A and by B give the worst violator at any α from their two heads, and a
/// release updates α in O(1). The loop is the one-at-a-time rule itself, at
/// O(n_c·log n_c) at worst (one sort per side) instead of O(n_c·n_slip) (issue 11), and
/// O(n_c) when the slip is on one side (the waves below). The worst violator is the
/// one with the largest excess per unit mass (the largest slip acceleration it would need);
/// with equal node masses on the pulley (every belt without material on it there) that is
/// the largest excess, exactly as before.
fn release_slipping(
    contacts: &PulleyContacts,
    pulley: &FrictionPulley,
    mass: &[f64],
    scratch: &mut StickScratch,
    known_torque: f64,
) -> usize {
    let nc = contacts.len();
    let r = pulley.radius;
    let (mut a_sum, mut m_sum) = sticking_sums(contacts, mass, scratch, |_, f, m| (f, m));
    let alpha = |torque: f64, a_sum: f64, m_sum: f64| {
        (torque + r * a_sum) / (pulley.inertia + r * r * m_sum)
    };
    // The common case: nothing slips at the first solve (one O(n_c) pass, no lists).
    let alpha0 = alpha(known_torque, a_sum, m_sum);
    let mut any = false;
    for k in 0..nc {
        let f = scratch.free[k] - mass[contacts.node[k]] * r * alpha0;
        scratch.force[k] = f;
        any |= f.abs() > scratch.limit[k];
    }
    if !any {
        return 0;
    }
    // Keys: excess per unit mass at α = 0, "+" side (A_k) and "−" side (B_k).
    scratch.key_pos.clear();
    scratch.key_neg.clear();
    for k in 0..nc {
        let inv_m = 1.0 / mass[contacts.node[k]];
        let limit = scratch.limit[k];
        scratch.key_pos.push((scratch.free[k] - limit) * inv_m);
        scratch.key_neg.push((-scratch.free[k] - limit) * inv_m);
    }
    let (mut torque, mut slipping) = (known_torque, 0);
    // Waves first: with E the largest excess on the other side (0 if none), every node on
    // the worst side whose excess exceeds E is the next in the one-at-a-time rule's order
    // on that side, and stays ahead of every node of the other side while it is released
    // (its excess grows as α moves away, the other side's shrink). So releasing that whole
    // prefix in one O(n_c) pass gives exactly the states of the one-at-a-time rule. A slip
    // arc, a sliding capstan or a brake is one or two waves (more when releases cascade);
    // slip on both sides (a loop settling on its pulleys stretches away from them both
    // ways) releases few per wave, and once a wave takes less than half of the violators
    // the rest goes to the sorted lists.
    const MAX_WAVES: usize = 8;
    for _ in 0..MAX_WAVES {
        let ra = r * alpha(torque, a_sum, m_sum);
        let (mut ep, mut en) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut violators = 0usize;
        for k in 0..nc {
            if scratch.sticking[k] {
                let (p, q) = (scratch.key_pos[k] - ra, scratch.key_neg[k] + ra);
                ep = ep.max(p);
                en = en.max(q);
                violators += usize::from(p > 0.0 || q > 0.0);
            }
        }
        if !(ep > 0.0 || en > 0.0) {
            finish(contacts, mass, scratch, r, |a, m| alpha(torque, a, m));
            return slipping;
        }
        let positive = ep >= en;
        let (keys, shift, top, other, sign) = if positive {
            (&scratch.key_pos, -ra, ep, en, 1.0)
        } else {
            (&scratch.key_neg, ra, en, ep, -1.0)
        };
        let threshold = other.max(0.0);
        let mut released = 0usize;
        for k in 0..nc {
            if !scratch.sticking[k] {
                continue;
            }
            let e = keys[k] + shift;
            // `>= top`: the worst itself always goes (ties with the other side included).
            if e > threshold || e >= top {
                let fk = sign * pulley.mu_kinetic * contacts.normal_force[k];
                scratch.force[k] = fk;
                scratch.sticking[k] = false;
                torque += r * fk;
                a_sum -= scratch.free[k];
                m_sum -= mass[contacts.node[k]];
                released += 1;
            }
        }
        slipping += released;
        if 2 * released < violators {
            break;
        }
    }
    let mut pos = std::mem::take(&mut scratch.list_pos);
    let mut neg = std::mem::take(&mut scratch.list_neg);
    // Each side in its fixed order, worst first (ties: lowest index first, as the scan did).
    sort_worst_first(&scratch.key_pos, &scratch.sticking, &mut pos);
    sort_worst_first(&scratch.key_neg, &scratch.sticking, &mut neg);
    let key_index = |c: u128| (c as u64) as usize;
    let (mut i, mut j) = (0, 0);
    loop {
        let ra = r * alpha(torque, a_sum, m_sum);
        // Skip released nodes (each was released through the other side's list).
        while i < pos.len() && !scratch.sticking[key_index(pos[i])] {
            i += 1;
        }
        while j < neg.len() && !scratch.sticking[key_index(neg[j])] {
            j += 1;
        }
        let ep = pos
            .get(i)
            .map_or(f64::NEG_INFINITY, |&c| scratch.key_pos[key_index(c)] - ra);
        let en = neg
            .get(j)
            .map_or(f64::NEG_INFINITY, |&c| scratch.key_neg[key_index(c)] + ra);
        // In mass-scaled units, m_k·(excess) > 0 exactly when the node violates.
        let (k, sign) = if ep >= en && ep > 0.0 {
            i += 1;
            (key_index(pos[i - 1]), 1.0)
        } else if en > 0.0 {
            j += 1;
            (key_index(neg[j - 1]), -1.0)
        } else {
            break;
        };
        let m = mass[contacts.node[k]];
        // The side's list found the violation (f = free − m·r·α beyond ±µs·N); it slips
        // with µk·N against it.
        let fk = sign * pulley.mu_kinetic * contacts.normal_force[k];
        scratch.force[k] = fk;
        scratch.sticking[k] = false;
        torque += r * fk;
        a_sum -= scratch.free[k];
        m_sum -= m;
        slipping += 1;
    }
    scratch.list_pos = pos;
    scratch.list_neg = neg;
    finish(contacts, mass, scratch, r, |a, m| alpha(torque, a, m));
    slipping
}

/// [`release_slipping`] for contacts with their own arms (rigid bodies resting on their
/// ends, [`PulleyContacts::arm`]): the pulley's surface moves at lever_k·ω under contact k
/// ([`PulleyContacts::lever`]) and its friction turns the pulley with arm_k·f_k, so a
/// sticking contact's force is f_k = free_k − m_k·lever_k·α and
/// α = (T + Σ_S arm_k·free_k) / (I + Σ_S m_k·arm_k·lever_k), T the known torque plus the
/// slipping contacts' moments Σ arm_k·f_k. The pulley then takes exactly the moment the
/// bodies receive: belt and pulley keep their angular momentum (as under creep friction).
///
/// With the levers unequal the excess per unit mass, (free_k ∓ µs·N_k)/m_k ∓ lever_k·α,
/// orders the candidates differently at each α, so the sorted lists of [`release_slipping`]
/// do not apply: the one-at-a-time rule itself, the worst violator (largest excess per unit
/// mass at the current α; ties: lowest index) released each round, O(n_c·n_slip). A drum
/// carries tens of bodies, not the thousands of nodes the lists are for.
fn release_slipping_arms(
    contacts: &PulleyContacts,
    pulley: &FrictionPulley,
    mass: &[f64],
    scratch: &mut StickScratch,
    known_torque: f64,
) -> usize {
    let nc = contacts.len();
    let r = pulley.radius;
    let (mut torque, mut slipping) = (known_torque, 0);
    loop {
        let (a_sum, m_sum) = sticking_sums(contacts, mass, scratch, |k, f, m| {
            let a = contacts.arm_at(k, r);
            (a * f, m * a * contacts.lever_at(k, r))
        });
        let alpha = (torque + a_sum) / (pulley.inertia + m_sum);
        let mut worst: Option<(usize, f64, f64)> = None;
        for k in 0..nc {
            if !scratch.sticking[k] {
                continue;
            }
            let m = mass[contacts.node[k]];
            let f = scratch.free[k] - m * (contacts.lever_at(k, r) * alpha);
            scratch.force[k] = f;
            let excess = (f.abs() - scratch.limit[k]) / m;
            if excess > 0.0 && worst.is_none_or(|(_, e, _)| excess > e) {
                worst = Some((k, excess, f.signum()));
            }
        }
        let Some((k, _, sign)) = worst else {
            return slipping;
        };
        let fk = sign * pulley.mu_kinetic * contacts.normal_force[k];
        scratch.force[k] = fk;
        scratch.sticking[k] = false;
        torque += contacts.arm_at(k, r) * fk;
        slipping += 1;
    }
}

/// Σ over the sticking contacts of `term(k, free_k, m_k)`, both parts: the numerator and
/// the denominator sums of the pulley's α (nodes: Σ free, Σ m; rigid bodies: with their
/// arms and levers).
fn sticking_sums(
    contacts: &PulleyContacts,
    mass: &[f64],
    scratch: &StickScratch,
    term: impl Fn(usize, f64, f64) -> (f64, f64),
) -> (f64, f64) {
    let (mut a_sum, mut m_sum) = (0.0, 0.0);
    for k in 0..contacts.len() {
        if scratch.sticking[k] {
            let (a, m) = term(k, scratch.free[k], mass[contacts.node[k]]);
            a_sum += a;
            m_sum += m;
        }
    }
    (a_sum, m_sum)
}

/// The sticking nodes' forces at the final α = `alpha`(A, M) of the slip loop, with the
/// sums A and M over the sticking nodes taken afresh (no running subtraction left in them).
fn finish(
    contacts: &PulleyContacts,
    mass: &[f64],
    scratch: &mut StickScratch,
    r: f64,
    alpha: impl Fn(f64, f64) -> f64,
) {
    let (a_sum, m_sum) = sticking_sums(contacts, mass, scratch, |_, f, m| (f, m));
    let ra = r * alpha(a_sum, m_sum);
    for k in 0..contacts.len() {
        if scratch.sticking[k] {
            scratch.force[k] = scratch.free[k] - mass[contacts.node[k]] * ra;
        }
    }
}

/// The friction force a contact can carry: the stick force `f` if within its static limit
/// `static_limit` (N), else µk·N in its direction. Returns (force, slipping).
fn limit(f: f64, static_limit: f64, normal: f64, pulley: &FrictionPulley) -> (f64, bool) {
    if f.abs() > static_limit {
        (pulley.mu_kinetic * normal * f.signum(), true)
    } else {
        (f, false)
    }
}

/// Each contact's static limit for this step (N), into `scratch.limit`: µk·N for a
/// contact that is sliding (it slid in the previous step, `scratch.sliding`) or that
/// lies next to a sliding one on the pulley (the slip front), µs·N for the others. With
/// `dt` infinite (quasi-static friction, the static relaxation) there is no motion to
/// remember: µs·N for every contact.
///
/// Why (docs/wrap-contact.md, "Session 10: the drums' stick–slip"). Coulomb's law: the
/// static coefficient holds a contact at rest; a contact that slides has only µk·N, so it
/// stops sliding when µk·N can stop it within the step, not as soon as its stick force
/// falls below µs·N. And a node is the belt over half an element either side of it: next
/// to a sliding node the slip front lies within its share of the arc, where the belt at
/// rest carries no friction in steady running (creep theory: the adhesion arc holds its
/// tension) and the sliding part µk, so the front advances into it at µk·N. Without
/// both, every node of a drive drum's slip arc loads to µs·N, breaks away, slides
/// µk·N for a few steps and sticks again: a force drop of (µs − µk)·N per node and
/// per break, the drums' stick–slip spikes. A belt at rest on its whole arc still breaks
/// away at µs·N.
fn static_limits(
    contacts: &PulleyContacts,
    pulley: &FrictionPulley,
    nodes: usize,
    dt: f64,
    scratch: &mut StickScratch,
) {
    let nc = contacts.len();
    scratch.limit.clear();
    scratch.slid.clear();
    if dt.is_finite() && !scratch.sliding.is_empty() {
        // Ascending: `apply` writes it so, and a checkpoint's lists are sorted on reading.
        let before = &scratch.sliding;
        debug_assert!(before.windows(2).all(|w| w[0] <= w[1]));
        scratch.slid.extend(
            contacts
                .node
                .iter()
                .map(|i| before.binary_search(i).is_ok()),
        );
    } else {
        scratch.slid.resize(nc, false);
    }
    // Contacts are listed in window order: k − 1 and k + 1 are the neighbours along the
    // belt when their nodes are.
    let next = |i: usize| if i + 1 == nodes { 0 } else { i + 1 };
    for k in 0..nc {
        let i = contacts.node[k];
        let front = scratch.slid[k]
            || (k > 0 && scratch.slid[k - 1] && next(contacts.node[k - 1]) == i)
            || (k + 1 < nc && scratch.slid[k + 1] && next(i) == contacts.node[k + 1]);
        let mu = if front {
            pulley.mu_kinetic
        } else {
            pulley.mu_static
        };
        scratch.limit.push(mu * contacts.normal_force[k]);
    }
}

/// Apply the solved contact forces to the nodes and sum their action on the pulley.
/// The belt points that slide are remembered in `scratch.sliding` (none when `remember`
/// is false: quasi-static friction).
fn apply(
    contacts: &PulleyContacts,
    scratch: &mut StickScratch,
    force: &mut [V2],
    (radius, remember): (f64, bool),
    slipping: usize,
    held_torque: Option<f64>,
) -> FrictionOutcome {
    scratch.sliding.clear();
    if remember && slipping > 0 {
        let nodes = contacts.node.iter().zip(&scratch.sticking);
        scratch
            .sliding
            .extend(nodes.filter(|(_, &stuck)| !stuck).map(|(&i, _)| i));
        scratch.sliding.sort_unstable();
    }
    let mut out = FrictionOutcome {
        slipping,
        held_torque,
        ..Default::default()
    };
    for k in 0..contacts.len() {
        let f = scratch.force[k];
        let t = perp(contacts.normal[k]);
        force[contacts.node[k]] -= t * f;
        out.force += t * f;
        out.tangential += f;
    }
    // Rigid bodies: each friction's moment with its own arm, the moment the body receives
    // (see [`release_slipping_arms`]); nodes: the radius, the sum as before to the bit.
    out.torque = if contacts.arm.is_empty() {
        radius * out.tangential
    } else {
        (0..contacts.len())
            .map(|k| contacts.arm_at(k, radius) * scratch.force[k])
            .sum()
    };
    out
}

/// The idler seen by the friction solve.
#[derive(Debug, Clone, Copy)]
pub struct FrictionIdler {
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia, kg·m².
    pub inertia: f64,
    /// Angular speed at t − Δt/2, rad/s.
    pub omega: f64,
    /// Static coefficient.
    pub mu_static: f64,
    /// Kinetic coefficient.
    pub mu_kinetic: f64,
}

/// Stick-force friction at one idler contact point (thesis eq. 4.103–4.117).
///
/// The contact point moves with (1 − γ)v_i + γv_{i+1}; the friction force f is shared by
/// the lever rule. Requiring zero relative tangential speed after the step gives
/// f = [v_n/Δt + (1−γ) t·F_i/m_i + γ t·F_{i+1}/m_{i+1}] / [(1−γ)²/m_i + γ²/m_{i+1} + R²/I]
/// (the thesis' eq. 4.114 has a sign slip in the R² term). Returns (f, slipping): the belt
/// receives −f t, the idler the torque R f.
pub fn idler_stick_friction(
    contact: &IdlerContact,
    idler: &FrictionIdler,
    v: &[V2],
    mass: &[f64],
    dt: f64,
    force: &mut [V2],
) -> (f64, bool) {
    point_stick_force(
        contact,
        idler.radius * idler.omega,
        idler.radius * idler.radius / idler.inertia,
        v,
        mass,
        dt,
        force,
        idler.mu_static * contact.normal_force,
        idler.mu_kinetic * contact.normal_force,
    )
}

/// DIN 22101 running resistance at one idler contact point: the stick force of
/// [`idler_stick_friction`] against the ground (a body that neither moves nor turns, R²/I =
/// 0), clipped to `limit` = f·(N + m_R·g) (static and kinetic alike). It stops the contact
/// point's tangential motion within the step if it can (a belt at rest under a smaller
/// net force stays at rest), and otherwise opposes it with the full limit. Returns
/// (f, sliding): the belt receives −f t.
pub fn running_resistance(
    contact: &IdlerContact,
    limit: f64,
    v: &[V2],
    mass: &[f64],
    dt: f64,
    force: &mut [V2],
) -> (f64, bool) {
    point_stick_force(contact, 0.0, 0.0, v, mass, dt, force, limit, limit)
}

/// The shared kernel of [`idler_stick_friction`] and [`running_resistance`]: the tangential
/// force f that brings the contact point of `contact` to the tangential speed
/// `surface_speed` of the body at the end of the step, for a body whose surface yields to it
/// with the compliance R²/I (`body_compliance`, 0 for the ground); applied if |f| ≤
/// `static_limit`, else `kinetic_limit` in its direction. Returns (f, slipping).
#[allow(clippy::too_many_arguments)]
#[inline]
fn point_stick_force(
    contact: &IdlerContact,
    surface_speed: f64,
    body_compliance: f64,
    v: &[V2],
    mass: &[f64],
    dt: f64,
    force: &mut [V2],
    static_limit: f64,
    kinetic_limit: f64,
) -> (f64, bool) {
    let n = v.len();
    let (i, j) = (contact.element, (contact.element + 1) % n);
    let g = contact.gamma;
    let t = perp(contact.normal);
    let vc = v[i] * (1.0 - g) + v[j] * g;
    let vn = t.dot(&vc) - surface_speed;
    let num = vn / dt + (1.0 - g) * t.dot(&force[i]) / mass[i] + g * t.dot(&force[j]) / mass[j];
    let den = (1.0 - g) * (1.0 - g) / mass[i] + g * g / mass[j] + body_compliance;
    let mut f = num / den;
    let slipping = f.abs() > static_limit;
    if slipping {
        f = kinetic_limit * f.signum();
    }
    force[i] -= t * (f * (1.0 - g));
    force[j] -= t * (f * g);
    (f, slipping)
}
