"""The one line before numba compiles (compare.cli.compile_notice): printed on a terminal when a kernel is compiled,
once, never on a cache hit (a second process), never off a terminal; a compile in the report's worker processes
reaches the parent's announcer."""
import importlib
import io
import subprocess
import sys
import textwrap

from compare.cli.compile_notice import MESSAGE, announcer, compile_notice

_SRC = textwrap.dedent('''
    import numba

    @numba.njit(cache=True)
    def kernel(x):
        return 2.0 * x + 1.0

    @numba.njit(cache=True, inline="always")
    def inlined(x):
        return x
''')


def _module(tmp_path, name):
    (tmp_path / f"{name}.py").write_text(_SRC)
    sys.path.insert(0, str(tmp_path))
    try:
        return importlib.import_module(name)  # by name, as numba's cache wants (it pickles the globals' module)
    finally:
        sys.path.remove(str(tmp_path))


def test_a_compile_is_announced_once_on_a_terminal_and_not_on_a_cache_hit(tmp_path):
    mod = _module(tmp_path, "fresh_kernels")
    buf = io.StringIO()
    with compile_notice(stream=buf, tty=True):
        assert mod.kernel(1.0) == 3.0
        assert mod.kernel(2) == 5.0  # a second signature compiles too: still one line
    assert buf.getvalue() == MESSAGE + "\n"
    # a new process finds the kernel in numba's disk cache: nothing cold, nothing compiled, nothing printed
    probe = textwrap.dedent(f'''
        import io, sys
        sys.path.insert(0, {str(tmp_path)!r})
        import fresh_kernels
        from compare.cli.compile_notice import compile_notice
        buf = io.StringIO()
        with compile_notice(stream=buf, tty=True):
            fresh_kernels.kernel(1.0)
        print(repr(buf.getvalue()))
    ''')
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:1] == ["''"], out.stdout


def test_nothing_is_printed_off_a_terminal(tmp_path):
    mod = _module(tmp_path, "quiet_kernels")
    buf = io.StringIO()
    with compile_notice(stream=buf):  # a StringIO is no terminal, as a log file or a pipe is not
        assert mod.kernel(1.0) == 3.0
    assert buf.getvalue() == ""


def _compile_in_worker(name):
    import importlib

    return importlib.import_module(name).kernel(1.0)  # the worker's sys.path is the parent's (spawn)


def test_a_compile_in_a_pool_worker_is_announced_once_in_the_parent(tmp_path):
    from compare.report.pool import process_pool

    _module(tmp_path, "pool_kernels")  # written, not yet compiled: the worker compiles it
    buf = io.StringIO()
    announce = announcer(stream=buf, tty=True)
    sys.path.insert(0, str(tmp_path))
    try:
        with process_pool(1, on_compile=announce) as pool:
            assert pool.submit(_compile_in_worker, "pool_kernels").result(timeout=120) == 3.0
        with compile_notice(announce=announce):  # a later compile in this process: the line was said already
            assert _module(tmp_path, "pool_kernels_2").kernel(1.0) == 3.0
    finally:
        sys.path.remove(str(tmp_path))
    assert buf.getvalue() == MESSAGE + "\n"


def test_off_a_terminal_there_is_no_announcer():
    assert announcer(stream=io.StringIO()) is None
