"""Imported first by every example: makes sure OpenMP threads wait passively.

On a busy machine, OpenMP threads that spin while they wait slow a multi-threaded solve down
many times (README, troubleshooting). pvpython and pvbatch link libgomp, which reads
OMP_WAIT_POLICY once when the program starts, so setting os.environ inside a script is too late.
When the variable is unset, this restarts the same command line once with OMP_WAIT_POLICY=PASSIVE
(Linux, serial runs only: under mpiexec MPI is already initialised, so set it in the shell)."""
import os
import sys


def _restart_with_passive_wait():
    if os.environ.get("OMP_WAIT_POLICY") or not os.path.exists("/proc/self/cmdline"):
        return
    if any(key in os.environ for key in ("OMPI_COMM_WORLD_SIZE", "PMI_RANK", "PMI_SIZE")):
        return
    with open("/proc/self/cmdline", "rb") as f:
        args = [a.decode() for a in f.read().split(b"\0") if a]
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(os.readlink("/proc/self/exe"), args, dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))


_restart_with_passive_wait()
