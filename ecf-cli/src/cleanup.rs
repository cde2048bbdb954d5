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
            if let Ok(list) = PENDING.lock() {
                for p in list.iter() {
                    let _ = if p.is_dir() {
                        std::fs::remove_dir_all(p)
                    } else {
                        std::fs::remove_file(p)
                    };
                }
            }
            eprintln!("interrupted: temporary files removed");
            std::process::exit(130);
        });
    });
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
