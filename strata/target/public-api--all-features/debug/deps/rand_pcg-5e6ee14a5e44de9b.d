/work/main/strata/target/public-api--all-features/debug/deps/rand_pcg-5e6ee14a5e44de9b.d: /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/lib.rs /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg128.rs /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg128cm.rs /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg64.rs

/work/main/strata/target/public-api--all-features/debug/deps/librand_pcg-5e6ee14a5e44de9b.rmeta: /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/lib.rs /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg128.rs /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg128cm.rs /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg64.rs

/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/lib.rs:
/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg128.rs:
/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg128cm.rs:
/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/rand_pcg-0.10.3/src/pcg64.rs:
