//! The FMU state functions: get, set, free, serialize and deserialize a snapshot of an instance (FMI 2.0 sec. 2.1.8).

use super::*;

fn state_handle(p: *mut std::ffi::c_void) -> usize {
    p as usize
}

fn unknown_state(inst: &mut Instance, func: &str, what: &str, h: usize) -> Status {
    inst.error(format!(
        "{func}: {what} = {h:#x} is not a live FMU state of this FMU (never created by fmi2GetFMUstate/fmi2DeSerializeFMUstate, or already freed)"
    ))
}

/// Stores a snapshot in the state `*slot` (a new one if `*slot` is null).
fn store_state(
    comp: &mut Component,
    func: &str,
    owner: usize,
    slot: &mut f::fmi2FMUstate,
    snap: Snapshot,
    bytes: Option<Vec<u8>>,
) -> Status {
    let h = state_handle(*slot);
    let mut r = registry();
    if h == 0 {
        let k = r.handle();
        let fmi3 = comp.v3.is_some();
        r.states.insert(
            k,
            StateBox {
                owner,
                snap,
                bytes,
                fmi3,
            },
        );
        *slot = k as f::fmi2FMUstate;
        Status::Ok
    } else if let Some(b) = r.states.get_mut(&h) {
        b.snap = snap;
        b.bytes = bytes;
        Status::Ok
    } else {
        drop(r);
        unknown_state(&mut comp.inst, func, "*FMUstate", h)
    }
}

/// The body of fmi2GetFMUstate and its FMI 3.0 counterpart (`f`: the function's name).
pub(super) unsafe fn get_fmu_state(
    c: *mut std::ffi::c_void,
    f: &str,
    FMUstate: *mut f::fmi2FMUstate,
) -> Status {
    // SAFETY: `c` as in `with`; FMUstate points to the importer's fmi2FMUstate variable, which
    // fmi2GetFMUstate writes (FMI 2.0 sec. 2.1.8); `as_mut` checks null.
    unsafe {
        with_status(c, f, |comp| {
            let Some(slot) = FMUstate.as_mut() else {
                return null_arg(&mut comp.inst, f, "FMUstate");
            };
            match comp.inst.try_get_state() {
                Ok(snap) => store_state(comp, f, c as usize, slot, snap, None),
                Err(s) => s,
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: f::fmi2Component, FMUstate: *mut f::fmi2FMUstate) -> S {
    // SAFETY: the arguments as the standard gives them, checked in `get_fmu_state`.
    status(unsafe { get_fmu_state(c, "fmi2GetFMUstate", FMUstate) })
}

/// The body of fmi2SetFMUstate and its FMI 3.0 counterpart (`f`: the function's name).
pub(super) unsafe fn set_fmu_state(
    c: *mut std::ffi::c_void,
    f: &str,
    FMUstate: f::fmi2FMUstate,
) -> Status {
    // SAFETY: `c` as in `with`; FMUstate is a handle only looked up in the registry, never
    // dereferenced.
    unsafe {
        with_status(c, f, |comp| {
            let h = state_handle(FMUstate);
            let r = registry();
            match r.states.get(&h) {
                Some(b) => comp.inst.set_state(&b.snap),
                None => {
                    drop(r);
                    unknown_state(&mut comp.inst, f, "FMUstate", h)
                }
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: f::fmi2Component, FMUstate: f::fmi2FMUstate) -> S {
    // SAFETY: the arguments as the standard gives them, checked in `set_fmu_state`.
    status(unsafe { set_fmu_state(c, "fmi2SetFMUstate", FMUstate) })
}

/// The body of fmi2FreeFMUstate and its FMI 3.0 counterpart (`f`: the function's name).
pub(super) unsafe fn free_fmu_state(
    c: *mut std::ffi::c_void,
    f: &str,
    FMUstate: *mut f::fmi2FMUstate,
) -> Status {
    // SAFETY: `c` as in `with`; FMUstate points to the importer's fmi2FMUstate variable, which
    // fmi2FreeFMUstate sets to null (FMI 2.0 sec. 2.1.8); `as_mut` checks null; the state
    // itself is a registry handle.
    unsafe {
        with_status(c, f, |comp| {
            let Some(slot) = FMUstate.as_mut() else {
                return null_arg(&mut comp.inst, f, "FMUstate");
            };
            let h = state_handle(*slot);
            if h == 0 {
                return Status::Ok;
            }
            let b = registry().states.remove(&h);
            match b {
                Some(b) => {
                    drop(b);
                    *slot = std::ptr::null_mut();
                    Status::Ok
                }
                None => unknown_state(&mut comp.inst, f, "*FMUstate", h),
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: f::fmi2Component,
    FMUstate: *mut f::fmi2FMUstate,
) -> S {
    // SAFETY: the arguments as the standard gives them, checked in `free_fmu_state`.
    status(unsafe { free_fmu_state(c, "fmi2FreeFMUstate", FMUstate) })
}

/// The serialized bytes of a live state (computed once), or None for an unknown handle.
fn with_state_bytes<T>(h: usize, f: impl FnOnce(&[u8]) -> T) -> Option<T> {
    let mut r = registry();
    let b = r.states.get_mut(&h)?;
    let fmi3 = b.fmi3;
    let bytes = b.bytes.get_or_insert_with(|| {
        if fmi3 {
            state::serialize3(&b.snap)
        } else {
            state::serialize(&b.snap)
        }
    });
    Some(f(bytes))
}

/// The body of fmi2SerializedFMUstateSize and its FMI 3.0 counterpart (`f`: the function's name).
pub(super) unsafe fn serialized_size(
    c: *mut std::ffi::c_void,
    f: &str,
    FMUstate: f::fmi2FMUstate,
    size: *mut usize,
) -> Status {
    // SAFETY: `c` as in `with`; size points to a writable size_t (FMI 2.0 sec. 2.1.8), null-
    // checked by `as_mut`; FMUstate is a registry handle.
    unsafe {
        with_status(c, f, |comp| {
            let Some(size) = size.as_mut() else {
                return null_arg(&mut comp.inst, f, "size");
            };
            let h = state_handle(FMUstate);
            match with_state_bytes(h, |b| b.len()) {
                Some(n) => {
                    *size = n;
                    Status::Ok
                }
                None => unknown_state(&mut comp.inst, f, "FMUstate", h),
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: f::fmi2Component,
    FMUstate: f::fmi2FMUstate,
    size: *mut usize,
) -> S {
    // SAFETY: the arguments as the standard gives them, checked in `serialized_size`.
    status(unsafe { serialized_size(c, "fmi2SerializedFMUstateSize", FMUstate, size) })
}

/// The body of fmi2SerializeFMUstate and its FMI 3.0 counterpart (`f`: the function's name).
pub(super) unsafe fn serialize_fmu_state(
    c: *mut std::ffi::c_void,
    f: &str,
    FMUstate: f::fmi2FMUstate,
    serializedState: *mut u8,
    size: usize,
) -> Status {
    // SAFETY: `c` as in `with`; serializedState is a writable buffer of `size` bytes (FMI 2.0
    // sec. 2.1.8): only bytes.len() <= size of them are written, after a null check.
    unsafe {
        with_status(c, f, |comp| {
            let h = state_handle(FMUstate);
            let r = with_state_bytes(h, |bytes| {
                if size < bytes.len() {
                    return Err(format!(
                        "{f}: buffer of {size} bytes, the state needs {} (fmi2SerializedFMUstateSize)",
                        bytes.len()
                    ));
                }
                let Some(out) = slice_mut(serializedState, bytes.len()) else {
                    return Err(format!("{f}: serializedState is a null pointer"));
                };
                out.copy_from_slice(bytes);
                Ok(())
            });
            match r {
                None => unknown_state(&mut comp.inst, f, "FMUstate", h),
                Some(Err(e)) => comp.inst.error(e),
                Some(Ok(())) => Status::Ok,
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: f::fmi2Component,
    FMUstate: f::fmi2FMUstate,
    serializedState: *mut f::fmi2Byte,
    size: usize,
) -> S {
    // SAFETY: the arguments as the standard gives them, checked in `serialize_fmu_state`.
    status(unsafe {
        serialize_fmu_state(
            c,
            "fmi2SerializeFMUstate",
            FMUstate,
            serializedState as *mut u8,
            size,
        )
    })
}

/// The body of fmi2DeSerializeFMUstate and its FMI 3.0 counterpart (`f`: the function's name).
pub(super) unsafe fn deserialize_fmu_state(
    c: *mut std::ffi::c_void,
    f: &str,
    serializedState: *const u8,
    size: usize,
    FMUstate: *mut f::fmi2FMUstate,
) -> Status {
    // SAFETY: `c` as in `with`; serializedState is an array of `size` bytes and FMUstate a
    // writable fmi2FMUstate variable (FMI 2.0 sec. 2.1.8), null-checked by `slice` and
    // `as_mut`; the bytes are copied.
    unsafe {
        with_status(c, f, |comp| {
            let (Some(data), Some(slot)) = (slice(serializedState, size), FMUstate.as_mut()) else {
                return null_arg(&mut comp.inst, f, "serializedState or FMUstate");
            };
            let parsed = if comp.v3.is_some() {
                state::deserialize3(data)
            } else {
                state::deserialize(data)
            };
            let snap = match parsed {
                Ok(s) => s,
                Err(e) => return comp.inst.error(format!("{f}: {e}")),
            };
            store_state(comp, f, c as usize, slot, snap, Some(data.to_vec()))
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: f::fmi2Component,
    serializedState: *const f::fmi2Byte,
    size: usize,
    FMUstate: *mut f::fmi2FMUstate,
) -> S {
    // SAFETY: the arguments as the standard gives them, checked in `deserialize_fmu_state`.
    status(unsafe {
        deserialize_fmu_state(
            c,
            "fmi2DeSerializeFMUstate",
            serializedState as *const u8,
            size,
            FMUstate,
        )
    })
}
