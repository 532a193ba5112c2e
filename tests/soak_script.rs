//! The soak (`scripts/soak.sh`, outside the test command: it plays for minutes) fails on a leak:
//! its memory verdict, run here on samples, passes growth of up to 10 % from minute 2 to the
//! end and fails more.

use std::process::Command;

fn verdict(samples: &[&str]) -> (bool, String) {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/soak.sh");
    let out = Command::new("bash").arg(script).arg("--judge-memory").args(samples).output().expect("run bash");
    let text = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.success(), text)
}

#[test]
fn the_soak_fails_when_memory_grows_more_than_ten_percent_after_two_minutes() {
    // Warm-up growth before minute 2 does not count.
    let (ok, text) = verdict(&["0:200", "60:380", "120:400", "300:420", "600:440"]);
    assert!(ok && text.contains("grew 10.0 %"), "{text}");
    let (ok, text) = verdict(&["0:200", "120:400", "300:420", "600:441"]);
    assert!(!ok && text.contains("a leak"), "{text}");
    // A soak too short to judge is not a pass.
    let (ok, text) = verdict(&["0:200", "60:210"]);
    assert!(!ok && text.contains("no memory sample at 2 minutes"), "{text}");
}
