//! `--out` on what is not a plain file: a FIFO and a device are written through and stay what
//! they are, a symbolic link stays a link to the new file, a directory is an error.
mod common;
use common::ecf;
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh temporary folder for one test, holding `hpt.csv` (high-pressure-torsion curves: their
/// fit takes milliseconds).
fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ecf-out-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(
        d.join("hpt.csv"),
        "p_MPa,u_mm,tau_MPa,series\n500,0.1,150,a\n500,0.3,250,a\n500,0.6,300,a\n500,1.0,320,a\n1000,0.1,200,b\n1000,0.3,330,b\n1000,0.6,400,b\n1000,1.0,430,b\n",
    )
    .unwrap();
    d
}

/// `ecf fit` of the folder's `hpt.csv` with `--out out`: (exit code, stdout, stderr).
fn fit_to(d: &Path, out: &Path) -> (i32, String, String) {
    ecf(&[
        "fit",
        d.join("hpt.csv").to_str().unwrap(),
        "--preset",
        "dry",
        "--out",
        out.to_str().unwrap(),
    ])
}

/// The names in a folder, sorted.
fn names(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The fitted configuration: JSON with its `"fit"` record.
fn assert_fitted(text: &str) {
    let v: serde_json::Value = serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert!(v["fit"]["params"].is_array(), "{text}");
}

#[test]
fn a_fifo_is_written_through_and_stays_a_fifo() {
    let d = folder("fifo");
    let fifo = d.join("pipe");
    let st = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("run mkfifo");
    assert!(st.success(), "mkfifo {}", fifo.display());
    // the reader blocks in open until ecf opens the FIFO for writing, then reads to the end
    let (tx, rx) = std::sync::mpsc::channel();
    let reader = fifo.clone();
    std::thread::spawn(move || {
        let _ = tx.send(std::fs::read_to_string(&reader));
    });
    let (code, _, err) = fit_to(&d, &fifo);
    assert_eq!(code, 0, "{err}");
    let t = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(t.is_fifo(), "{} is no longer a FIFO: {t:?}", fifo.display());
    // (a reader still waiting, when the FIFO was replaced, is left behind)
    let got = rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("the reader got nothing")
        .expect("read the FIFO");
    assert_fitted(&got);
    assert_eq!(names(&d), ["hpt.csv", "pipe"], "no temporary file");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_character_device_is_written_through_and_stays_a_device() {
    let d = folder("device");
    let dev = d.join("null");
    // a copy of /dev/null (never the real one); mknod needs root (CI runs as root): without
    // it, or where the container may not open the node, the test says why and passes
    match Command::new("mknod")
        .arg(&dev)
        .args(["c", "1", "3"])
        .output()
    {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            eprintln!(
                "skipped: mknod {} c 1 3 failed (not root?): {}",
                dev.display(),
                String::from_utf8_lossy(&o.stderr).trim()
            );
            std::fs::remove_dir_all(&d).ok();
            return;
        }
        Err(e) => {
            eprintln!("skipped: cannot run mknod: {e}");
            std::fs::remove_dir_all(&d).ok();
            return;
        }
    }
    if let Err(e) = std::fs::OpenOptions::new().write(true).open(&dev) {
        eprintln!("skipped: {} cannot be opened: {e}", dev.display());
        std::fs::remove_dir_all(&d).ok();
        return;
    }
    let (code, out, err) = fit_to(&d, &dev);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("written to"), "{out}");
    let t = std::fs::symlink_metadata(&dev).unwrap().file_type();
    assert!(
        t.is_char_device(),
        "{} is no longer a character device: {t:?}",
        dev.display()
    );
    assert_eq!(names(&d), ["hpt.csv", "null"], "no temporary file");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_symbolic_link_stays_and_its_target_gets_the_configuration() {
    let d = folder("link");
    let file = d.join("fitted.json");
    std::fs::write(&file, "previous result\n").unwrap();
    let link = d.join("latest.json");
    std::os::unix::fs::symlink("fitted.json", &link).unwrap();
    let (code, _, err) = fit_to(&d, &link);
    assert_eq!(code, 0, "{err}");
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink(),
        "{} was replaced",
        link.display()
    );
    assert_eq!(std::fs::read_link(&link).unwrap(), Path::new("fitted.json"));
    assert_fitted(&std::fs::read_to_string(&file).unwrap());
    assert_eq!(
        names(&d),
        ["fitted.json", "hpt.csv", "latest.json"],
        "no temporary file"
    );
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_dangling_link_gets_its_target_created_where_the_folder_exists() {
    let d = folder("dangling");
    let link = d.join("latest.json");
    std::os::unix::fs::symlink("new.json", &link).unwrap();
    let (code, _, err) = fit_to(&d, &link);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_fitted(&std::fs::read_to_string(d.join("new.json")).unwrap());
    // a link into a folder that does not exist: an error naming both, nothing written
    let lost = d.join("lost.json");
    std::os::unix::fs::symlink("missing/new.json", &lost).unwrap();
    let (code, _, err) = fit_to(&d, &lost);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(&format!("--out {}", lost.display())) && err.contains("missing/new.json"),
        "{err}"
    );
    assert!(std::fs::symlink_metadata(&lost)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(
        names(&d),
        ["hpt.csv", "latest.json", "lost.json", "new.json"]
    );
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_directory_is_an_error_and_stays_as_it_was() {
    let d = folder("dir");
    let sub = d.join("results");
    std::fs::create_dir(&sub).unwrap();
    std::fs::write(sub.join("keep.txt"), "kept\n").unwrap();
    let (code, out, err) = fit_to(&d, &sub);
    assert_eq!(code, 2, "{out}");
    assert!(
        err.contains(&format!(
            "--out {}: is a directory; expected a file path",
            sub.display()
        )),
        "{err}"
    );
    assert!(sub.is_dir());
    assert_eq!(names(&sub), ["keep.txt"]);
    assert_eq!(
        std::fs::read_to_string(sub.join("keep.txt")).unwrap(),
        "kept\n"
    );
    assert_eq!(
        names(&d),
        ["hpt.csv", "results"],
        "nothing written beside it"
    );
    std::fs::remove_dir_all(&d).ok();
}
