//! The recorder's memory bound: decimation keeps a uniform grid over the whole run.
use crate::common::case_h;
use beltrs::record::Channels;
use beltrs::Simulation;

#[test]
fn bounded_recording_decimates_to_a_uniform_grid() {
    let scene = case_h(89);
    let mut full = Simulation::new(&scene).unwrap();
    full.begin_recording(Channels::default(), 1, usize::MAX);
    full.advance(1000).unwrap();
    full.end_recording().unwrap();
    assert_eq!(full.recording.len(), 1001);

    let max = 10;
    let mut bounded = Simulation::new(&scene).unwrap();
    bounded.begin_recording(Channels::default(), 1, max);
    bounded.advance(1000).unwrap();
    bounded.end_recording().unwrap();
    let r = &bounded.recording;
    assert!(r.len() <= max && r.len() >= max / 2, "{} samples", r.len());
    // 1000 steps into 10 samples: the interval doubled to 128 steps (1000/128 → 8 intervals).
    let every = bounded.record_every() as usize;
    assert_eq!(every, 128);
    // Kept samples are exact copies of the unbounded ones at every `every`-th step.
    let n = full.recording.nodes;
    for (k, &t) in r.time.iter().enumerate() {
        let i = k * every;
        assert_eq!(t.to_bits(), full.recording.time[i].to_bits());
        assert_eq!(
            r.tension[k * n..(k + 1) * n],
            full.recording.tension[i * n..(i + 1) * n]
        );
        assert_eq!(
            r.energy[k * 7..(k + 1) * 7],
            full.recording.energy[i * 7..(i + 1) * 7]
        );
    }
    // The whole run is covered: the last sample is within one interval of the end.
    assert!(full.state.step as usize - (r.len() - 1) * every < every);
    // Memory: capacity never grew past the bound.
    let per = r.bytes_per_sample();
    assert_eq!(per, 8 * (8 + 5 * 89 + 13 * 2));
    assert!(bounded.recording.allocated_bytes() <= max * per);
}
