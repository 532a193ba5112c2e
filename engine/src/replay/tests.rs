use std::path::Path;

use super::*;

fn sample() -> ReplayWriter {
    let header = ReplayHeader {
        level_id: "cellar".into(),
        level_hash: 0x1234_5678_9abc_def0,
        tick_rate: 60,
        seed: 42,
        settings: vec![("gi.enabled".into(), "true".into()), ("fov_deg".into(), "70".into())],
        command_size: 3,
    };
    let mut w = ReplayWriter::new(header);
    for t in 0..5u8 {
        w.push(&[t, t + 1, t + 2], 1000 + t as u64);
    }
    w
}

#[test]
fn round_trip() {
    let w = sample();
    let r = Replay::parse(&w.to_bytes(), Path::new("x.replay")).unwrap();
    assert_eq!(&r.header, w.header());
    assert_eq!(r.tick_count(), 5);
    assert_eq!(r.command(3), &[3, 4, 5]);
    assert_eq!(r.state_hash(4), 1004);
    assert_eq!(r.header.setting("fov_deg"), Some("70"));
}

#[test]
fn every_truncation_is_refused_by_name() {
    let bytes = sample().to_bytes();
    for len in 0..bytes.len() {
        let e = Replay::parse(&bytes[..len], Path::new("cut.replay")).unwrap_err();
        let msg = e.to_string();
        assert!(msg.starts_with("cut.replay: "), "{msg}");
        assert!(
            matches!(e.kind, ReplayErrorKind::Truncated { .. } | ReplayErrorKind::NotAReplay),
            "length {len}: {msg}"
        );
    }
}

#[test]
fn every_flipped_byte_is_refused() {
    let bytes = sample().to_bytes();
    for i in 0..bytes.len() {
        for bit in [0x01u8, 0x80] {
            let mut b = bytes.clone();
            b[i] ^= bit;
            assert!(Replay::parse(&b, Path::new("x.replay")).is_err(), "byte {i} bit {bit:#x} went unnoticed");
        }
    }
}

#[test]
fn unknown_versions_and_other_files_are_named() {
    let mut bytes = sample().to_bytes();
    bytes[8..12].copy_from_slice(&7u32.to_le_bytes());
    let msg = Replay::parse(&bytes, Path::new("new.replay")).unwrap_err().to_string();
    assert!(msg.contains("version 7") && msg.contains("reads version 1"), "{msg}");
    let msg = Replay::parse(b"P6 640 480", Path::new("a.ppm")).unwrap_err().to_string();
    assert!(msg.contains("not a Headlamp replay"), "{msg}");
    let mut long = sample().to_bytes();
    long.push(0);
    let msg = Replay::parse(&long, Path::new("x.replay")).unwrap_err().to_string();
    assert!(msg.contains("corrupted"), "{msg}");
}

#[test]
fn save_replaces_the_file_whole() {
    let dir = std::env::temp_dir().join(format!("hl-replay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("a.replay");
    sample().save(&path).unwrap();
    assert_eq!(Replay::read(&path).unwrap().tick_count(), 5);
    assert!(!dir.join("a.replay.partial").exists());
    let msg = Replay::read(&dir.join("missing.replay")).unwrap_err().to_string();
    assert!(msg.contains("missing.replay"), "{msg}");
    std::fs::remove_dir_all(&dir).unwrap();
}
