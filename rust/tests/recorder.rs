//! The recorder's memory bound: decimation keeps a uniform grid over the whole run.
use crate::common::case_h;
use beltrs::record::Channels;
use beltrs::Simulation;

/// Every channel, energies and contact forces included (they are opt-in).
const ALL: Channels = Channels {
    tension: true,
    node_position: true,
    node_velocity: true,
    energy: true,
    contact_forces: true,
};

#[test]
fn bounded_recording_decimates_to_a_uniform_grid() {
    let scene = case_h(89);
    let mut full = Simulation::new(&scene).unwrap();
    full.begin_recording(ALL, 1, usize::MAX);
    full.advance(1000).unwrap();
    full.end_recording().unwrap();
    assert_eq!(full.recording.len(), 1001);

    let max = 10;
    let mut bounded = Simulation::new(&scene).unwrap();
    bounded.begin_recording(ALL, 1, max);
    bounded.advance(1000).unwrap();
    bounded.end_recording().unwrap();
    let r = &bounded.recording;
    assert!(r.len() <= max && r.len() >= max / 2, "{} samples", r.len());
    // 1000 steps into 10 samples: the interval doubled to 128 steps (1000/128 → 8 intervals).
    let every = bounded.record_every() as usize;
    assert_eq!(every, 128);
    // Kept samples are exact copies of the unbounded ones at every `every`-th step, and the
    // last one is the end of the run (step 1000, off the doubled grid).
    let n = full.recording.nodes;
    let last = r.len() - 1;
    for (k, &t) in r.time.iter().enumerate() {
        let i = if k == last { 1000 } else { k * every };
        assert_eq!(t.to_bits(), full.recording.time[i].to_bits());
        assert_eq!(
            r.tension[k * n..(k + 1) * n],
            full.recording.tension[i * n..(i + 1) * n]
        );
        assert_eq!(
            r.energy[k * 7..(k + 1) * 7],
            full.recording.energy[i * 7..(i + 1) * 7]
        );
        let w = 2 * n; // contact forces: pulleys × nodes per instant
        assert_eq!(
            r.contact_normal[k * w..(k + 1) * w],
            full.recording.contact_normal[i * w..(i + 1) * w]
        );
    }
    // The whole run is covered: the grid reaches within one interval of the end, and the
    // end itself is sampled.
    assert!(1000 - (last - 1) * every <= every);
    assert_eq!(r.time[last].to_bits(), bounded.state.time.to_bits());
    // Memory: capacity never grew past the bound.
    let per = r.bytes_per_sample();
    assert_eq!(per, 8 * (8 + 5 * 89 + 13 * 2 + 3 * 2 * 89));
    assert!(bounded.recording.allocated_bytes() <= max * per);
}
