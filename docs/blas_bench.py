#!/usr/bin/python3
"""CPU BLAS micro-benchmark for Debian's LibTorch 1.13 (python3-torch).

Which libblas.so.3 is used is decided by the dynamic loader (update-alternatives
or LD_LIBRARY_PATH), so run this script once per BLAS, e.g.

  /usr/bin/python3 docs/blas_bench.py --threads 2                        # system default
  LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/blas /usr/bin/python3 docs/blas_bench.py --threads 1
  LD_LIBRARY_PATH=/tmp/blas-variants/openmp/usr/lib/x86_64-linux-gnu/openblas-openmp \
      OPENBLAS_NUM_THREADS=1 /usr/bin/python3 docs/blas_bench.py --threads 2

It prints one JSON line: the BLAS/LAPACK/OpenMP libraries actually mapped into
the process (from /proc/self/maps), the environment, and the median wall time
in ms of each workload (batch 16 / 8, float32, CPU):

  lin     Linear(90 -> 9600), x 16x90, forward + backward
  bmm     batched matmul 16 x (256x256 @ 256x256), forward + backward
  convT   ConvTranspose2d(128,64,4,2,1) + BatchNorm2d + ReLU, 16x128x40x40 -> 80x80, fwd + bwd
  conv    Conv2d(32,3,3,padding=1), 16x32x160x160, fwd + bwd
  dec     patch decoder (Linear 90->5*5*512, 5x [ConvT(c,c/2,4,2,1)+BN+ReLU], Conv2d(16,3,3,p=1)),
          one Adam step (fwd, L1 loss, bwd, step) at batch 8
"""
import argparse
import json
import os
import statistics
import time

import torch
import torch.nn as nn


def mapped_libs():
    keys = ("blas", "lapack", "atlas", "gomp", "dnnl", "libtorch_cpu")
    libs = set()
    with open("/proc/self/maps") as f:
        for line in f:
            parts = line.split()
            if len(parts) >= 6 and any(k in parts[5] for k in keys):
                libs.add(os.path.realpath(parts[5]))
    return sorted(libs)


def timeit(fn, reps, budget_s, warmup):
    for _ in range(warmup):
        fn()
    times = []
    t_start = time.perf_counter()
    while len(times) < reps:
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) * 1e3)
        # stop early for slow configurations, but keep at least 3 samples
        if len(times) >= 3 and time.perf_counter() - t_start > budget_s:
            break
    return statistics.median(times), len(times)


def make_workloads():
    torch.manual_seed(0)
    w = {}

    lin = nn.Linear(90, 9600)
    x_lin = torch.randn(16, 90, requires_grad=True)

    def f_lin():
        lin.zero_grad(set_to_none=True)
        x_lin.grad = None
        lin(x_lin).sum().backward()
    w["lin"] = (f_lin, 2)

    a = torch.randn(16, 256, 256, requires_grad=True)
    b = torch.randn(16, 256, 256, requires_grad=True)

    def f_bmm():
        a.grad = None
        b.grad = None
        torch.matmul(a, b).sum().backward()
    w["bmm"] = (f_bmm, 2)

    blk = nn.Sequential(nn.ConvTranspose2d(128, 64, 4, stride=2, padding=1),
                        nn.BatchNorm2d(64), nn.ReLU())
    x_blk = torch.randn(16, 128, 40, 40, requires_grad=True)

    def f_convT():
        blk.zero_grad(set_to_none=True)
        x_blk.grad = None
        y = blk(x_blk)
        assert y.shape == (16, 64, 80, 80)
        y.sum().backward()
    w["convT"] = (f_convT, 1)

    conv = nn.Conv2d(32, 3, 3, padding=1)
    x_conv = torch.randn(16, 32, 160, 160, requires_grad=True)

    def f_conv():
        conv.zero_grad(set_to_none=True)
        x_conv.grad = None
        conv(x_conv).sum().backward()
    w["conv"] = (f_conv, 1)

    class PatchDecoder(nn.Module):
        def __init__(self):
            super().__init__()
            self.fc = nn.Linear(90, 5 * 5 * 512)
            layers = []
            c = 512
            for _ in range(5):
                layers += [nn.ConvTranspose2d(c, c // 2, 4, stride=2, padding=1),
                           nn.BatchNorm2d(c // 2), nn.ReLU()]
                c //= 2
            layers.append(nn.Conv2d(c, 3, 3, padding=1))
            self.net = nn.Sequential(*layers)

        def forward(self, z):
            return self.net(self.fc(z).view(-1, 512, 5, 5))

    dec = PatchDecoder()
    opt = torch.optim.Adam(dec.parameters(), lr=1e-4)
    z = torch.randn(8, 90)
    target = torch.randn(8, 3, 160, 160)

    def f_dec():
        opt.zero_grad(set_to_none=True)
        out = dec(z)
        assert out.shape == (8, 3, 160, 160)
        loss = nn.functional.l1_loss(out, target)
        loss.backward()
        opt.step()
    w["dec"] = (f_dec, 1)
    return w


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--threads", type=int, default=0,
                   help="torch.set_num_threads value (0 = leave torch's default)")
    p.add_argument("--reps", type=int, default=5)
    p.add_argument("--budget", type=float, default=5.0,
                   help="seconds per workload after which to stop (min 3 reps)")
    p.add_argument("--workloads", default="lin,bmm,convT,conv,dec")
    p.add_argument("--label", default="")
    p.add_argument("--profile", action="store_true",
                   help="print which aten ops (mkldnn / slow_conv / mm) each workload hits")
    args = p.parse_args()

    default_threads = torch.get_num_threads()
    if args.threads:
        torch.set_num_threads(args.threads)
    torch.set_grad_enabled(True)
    work = make_workloads()

    if args.profile:
        from torch.profiler import profile
        for name in args.workloads.split(","):
            fn, _ = work[name]
            fn()
            with profile() as prof:
                fn()
            ops = sorted({e.name for e in prof.events()
                          if any(k in e.name for k in ("conv", "mm", "mkldnn", "matmul"))})
            print(name, ops)
        print("mkldnn available:", torch.backends.mkldnn.is_available())
        return

    loadavg0 = os.getloadavg()[0]
    res = {}
    for name in args.workloads.split(","):
        fn, warm = work[name]
        med, n = timeit(fn, args.reps, args.budget, warm)
        res[name] = round(med, 2)
        res[name + "_n"] = n
    out = {
        "label": args.label,
        "torch_threads": torch.get_num_threads(),
        "torch_default_threads": default_threads,
        "env": {k: os.environ[k] for k in ("LD_LIBRARY_PATH", "OMP_NUM_THREADS",
                                           "OPENBLAS_NUM_THREADS") if k in os.environ},
        "libs": [l for l in mapped_libs() if "blas" in l or "lapack" in l or "atlas" in l],
        "load": [round(loadavg0, 2), round(os.getloadavg()[0], 2)],
        "ms": res,
    }
    print(json.dumps(out), flush=True)


if __name__ == "__main__":
    main()
