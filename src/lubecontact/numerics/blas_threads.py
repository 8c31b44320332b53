"""One BLAS thread for the duration of a solve (threadpoolctl).

The solve's BLAS calls are small (vector norms and dots of GMRES and Anderson, SuperLU's
dense kernels of a 2-D problem), so threads only add synchronisation; where other
processes share the cores (a parallel workflow) an idle-spinning OpenBLAS thread made each
call 10-100 times slower (measured on the 2-core project machine). The caller's setting is restored
after the block.
"""

from __future__ import annotations

from functools import cache

from threadpoolctl import ThreadpoolController


@cache
def _controller() -> ThreadpoolController:
    """The BLAS thread pools of numpy and scipy, looked up once per process."""
    return ThreadpoolController()


def one_blas_thread():
    """Context manager: BLAS limited to one thread inside the block (module docstring)."""
    return _controller().limit(limits=1, user_api="blas")
