//! The seccomp filter bubblewrap loads into every sandbox (`--seccomp FD`): what no Tick 2 and
//! no javac needs and what widens the kernel a submission can reach is refused with EPERM:
//! new user namespaces (`unshare`, `clone` with `CLONE_NEWUSER`, and `clone3`, refused with
//! ENOSYS so that the C library falls back to `clone`, whose flags the filter can read), joining
//! namespaces, `ptrace` and reading or writing another process's memory, the kernel keyring,
//! BPF, perf events, userfaultfd, io_uring, and loading kernels or modules.
//!
//! Hand-written classic BPF, 48 instructions: a fixed list, checked by the sandbox's tests on
//! this machine. Any other architecture than the one whitted was built for (an i386 call on
//! x86-64) and the whole x32 ABI (numbers from bit 30 up) are refused.
//!
//! Why not rust-vmm's `seccompiler` (0.5.0, pure Rust, what guards Firecracker's microVMs): it
//! was ported and measured. Its cost is no reason: it builds in 0.44 s (libc is already in the
//! tree), adds 24 KiB to the stripped binary (8,176,224 to 8,200,992 bytes), and the port
//! passed the sandbox's test. Its shape is: it builds allowlists, where
//! exact numbers are what is wanted, and this filter is a denylist (an allowlist for a JVM and
//! javac would list every call HotSpot and glibc make, and break with their versions):
//! - one action for every match: the refused calls want EPERM and `clone3` ENOSYS (glibc falls
//!   back to `clone`, whose flags a filter can read, only on ENOSYS; EPERM there stops every
//!   thread the JVM starts). Two filters need bubblewrap's `--add-seccomp-fd` (0.5.0 on;
//!   Debian 11 ships 0.4.1), or every refusal becomes ENOSYS, as the port did;
//! - no range: on x86-64 the x32 ABI's calls come with the x86-64 architecture and bit 30 set,
//!   so a denylist of exact numbers must list each refused call's x32 number as well (the
//!   port added `nr | 0x4000_0000`; x32's own numbers, `ptrace` 521, `process_vm_readv` 539,
//!   `process_vm_writev` 540, `kexec_load` 528, need a table kept by hand), where one `JGE`
//!   refuses them all here;
//! - 201 instructions to these 48, and an allowed call walks two per listed call.
//!
//! A call of another architecture is killed there rather than refused: as good here.

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
