//! The seccomp filter bubblewrap loads into every sandbox (`--seccomp FD`): what no Tick 2 and
//! no javac needs and what widens the kernel a submission can reach is refused with EPERM:
//! new user namespaces (`unshare`, `clone` with `CLONE_NEWUSER`, and `clone3`, refused with
//! ENOSYS so that the C library falls back to `clone`, whose flags the filter can read), joining
//! namespaces, `ptrace` and reading or writing another process's memory, the kernel keyring,
//! BPF, perf events, userfaultfd, io_uring, and loading kernels or modules.
//!
//! Hand-written classic BPF, a few dozen instructions: the maintained generators are
//! libseccomp (a C library and a build dependency) or crates that bring their own JSON
//! compilers; this filter is a fixed list, checked by the sandbox's tests on this machine.
//! Any other architecture than the one whitted was built for (an i386 call on x86-64, the x32
//! ABI) is refused whole.

/// One classic BPF instruction, as the kernel's `struct sock_filter` lays it out.
#[derive(Clone, Copy)]
struct Op {
    code: u16,
    jt: u8,
    jf: u8,
    k: u32,
}

const LD_W_ABS: u16 = 0x20; // BPF_LD | BPF_W | BPF_ABS
const JEQ_K: u16 = 0x15; // BPF_JMP | BPF_JEQ | BPF_K
const JGE_K: u16 = 0x35; // BPF_JMP | BPF_JGE | BPF_K
const JSET_K: u16 = 0x45; // BPF_JMP | BPF_JSET | BPF_K
const RET_K: u16 = 0x06; // BPF_RET | BPF_K

const ALLOW: u32 = 0x7fff_0000;
const ERRNO: u32 = 0x0005_0000;
const EPERM: u32 = 1;
const ENOSYS: u32 = 38;
const CLONE_NEWUSER: u32 = 0x1000_0000;

/// `struct seccomp_data`: the call's number, its architecture, its first argument's low word.
const NR: u32 = 0;
const ARCH: u32 = 4;
const ARG0_LOW: u32 = 16;

/// The calls of this architecture: (audit arch, clone, clone3, refused).
#[cfg(target_arch = "x86_64")]
const CALLS: (u32, u32, u32, &[u32]) = (
    0xC000_003E,
    56,
    435,
    // ptrace, unshare, setns, process_vm_readv, process_vm_writev, keyctl, add_key,
    // request_key, bpf, perf_event_open, userfaultfd, io_uring_setup, kexec_load,
    // kexec_file_load, init_module, finit_module, delete_module.
    &[
        101, 272, 308, 310, 311, 250, 248, 249, 321, 298, 323, 425, 246, 320, 175, 313, 176,
    ],
);
#[cfg(target_arch = "aarch64")]
const CALLS: (u32, u32, u32, &[u32]) = (
    0xC000_00B7,
    220,
    435,
    &[
        117, 97, 268, 270, 271, 219, 217, 218, 280, 241, 282, 425, 104, 294, 105, 273, 106,
    ],
);

/// The filter's bytes, as bubblewrap reads them from the descriptor it is given; None on an
/// architecture without a list here (the sandbox then runs without one).
pub fn program() -> Option<Vec<u8>> {
    #[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
    {
        let ops = ops(CALLS);
        Some(
            ops.iter()
                .flat_map(|op| {
                    let mut bytes = op.code.to_ne_bytes().to_vec();
                    bytes.extend([op.jt, op.jf]);
                    bytes.extend(op.k.to_ne_bytes());
                    bytes
                })
                .collect(),
        )
    }
    #[cfg(not(any(target_arch = "x86_64", target_arch = "aarch64")))]
    None
}

#[allow(dead_code)]
fn ops((arch, clone, clone3, refused): (u32, u32, u32, &[u32])) -> Vec<Op> {
    let op = |code, jt, jf, k| Op { code, jt, jf, k };
    let mut ops = vec![
        op(LD_W_ABS, 0, 0, ARCH),
        // Another architecture: refused whole.
        op(JEQ_K, 1, 0, arch),
        op(RET_K, 0, 0, ERRNO | EPERM),
        op(LD_W_ABS, 0, 0, NR),
        // The x32 ABI's numbers (bit 30): refused.
        op(JGE_K, 0, 1, 0x4000_0000),
        op(RET_K, 0, 0, ERRNO | EPERM),
        op(JEQ_K, 0, 1, clone3),
        op(RET_K, 0, 0, ERRNO | ENOSYS),
        // clone with CLONE_NEWUSER: refused; any other clone: allowed.
        op(JEQ_K, 0, 3, clone),
        op(LD_W_ABS, 0, 0, ARG0_LOW),
        op(JSET_K, 0, 1, CLONE_NEWUSER),
        op(RET_K, 0, 0, ERRNO | EPERM),
    ];
    // After the clone test the accumulator may hold the flags: load the number again.
    ops.push(op(LD_W_ABS, 0, 0, NR));
    for &nr in refused {
        ops.push(op(JEQ_K, 0, 1, nr));
        ops.push(op(RET_K, 0, 0, ERRNO | EPERM));
    }
    ops.push(op(RET_K, 0, 0, ALLOW));
    ops
}
