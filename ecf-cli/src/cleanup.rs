//! Files and folders a command is writing, removed if it is interrupted (SIGINT, SIGTERM, SIGHUP): nothing half-written stays behind.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Installs the signal handler once: it removes every pending path and exits with 130.
pub fn install() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // without a handler (e.g. one is already installed) an interrupt leaves the files;
        // that is no reason to refuse the command
        let _ = ctrlc::set_handler(|| {
            // the lock is held until the process exits: no folder is created meanwhile
            // (`create_dir_all` takes it), while the command's own thread may still be
            // writing
            let list = PENDING.lock().unwrap_or_else(|e| e.into_inner());
            for p in list.iter() {
                remove(p);
            }
            eprintln!("interrupted: temporary files removed");
            std::process::exit(130);
        });
    });
}

/// Removes `p` for good while another thread may still write into it: first moved aside
/// (so that no file can be created under its name any more), then removed, again if a file
/// created at the moment of the move kept the folder from going.
fn remove(p: &Path) {
    let aside = p.with_extension("removing");
    let gone = if std::fs::rename(p, &aside).is_ok() {
        aside
    } else {
        p.to_path_buf()
    };
    for _ in 0..5 {
        let _ = if gone.is_dir() {
            std::fs::remove_dir_all(&gone)
        } else {
            std::fs::remove_file(&gone)
        };
        if !gone.exists() {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// `std::fs::create_dir_all`, never while an interrupt is removing the pending paths (it
/// would bring a removed folder back).
pub fn create_dir_all(dir: &Path) -> std::io::Result<()> {
    let _held = PENDING.lock().unwrap_or_else(|e| e.into_inner());
    std::fs::create_dir_all(dir)
}

/// A temporary file or folder: removed when the guard is dropped or the command is interrupted.
pub struct Pending(PathBuf);

impl Pending {
    /// Registers `path` (not created here).
    pub fn new(path: PathBuf) -> Self {
        if let Ok(mut l) = PENDING.lock() {
            l.push(path.clone());
        }
        Pending(path)
    }

    /// The path.
    pub fn path(&self) -> &Path {
        &self.0
    }

    /// The file was renamed to its final name: nothing left to remove.
    pub fn done(self) {
        self.forget();
        std::mem::forget(self);
    }

    fn forget(&self) {
        if let Ok(mut l) = PENDING.lock() {
            l.retain(|p| p != &self.0);
        }
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        self.forget();
        let _ = if self.0.is_dir() {
            std::fs::remove_dir_all(&self.0)
        } else {
            std::fs::remove_file(&self.0)
        };
    }
}
