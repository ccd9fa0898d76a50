"""The one line before numba compiles (compare.compile_notice): printed on a terminal when a kernel is compiled,
once, never on a cache hit (a second process), never off a terminal."""
import importlib
import io
import subprocess
import sys
import textwrap

from compare.cli.compile_notice import MESSAGE, cold_kernels, compile_notice

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
    assert cold_kernels([mod]) == ["fresh_kernels.kernel"]  # inlined kernels have no cache of their own
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
        from compare.cli.compile_notice import cold_kernels, compile_notice
        print(cold_kernels([fresh_kernels]))
        buf = io.StringIO()
        with compile_notice(stream=buf, tty=True):
            fresh_kernels.kernel(1.0)
        print(repr(buf.getvalue()))
    ''')
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:2] == ["[]", "''"], out.stdout


def test_nothing_is_printed_off_a_terminal(tmp_path):
    mod = _module(tmp_path, "quiet_kernels")
    buf = io.StringIO()
    with compile_notice(stream=buf):  # a StringIO is no terminal, as a log file or a pipe is not
        assert mod.kernel(1.0) == 3.0
    assert buf.getvalue() == ""


def test_the_reduced_models_kernels_are_found():
    """cold_kernels reads numba's cache index for every kernel of the reduced models without failing (it returns
    [] on failure, which would silence the notice): a kernel renamed in the index's layout shows up here."""
    from numba.core.dispatcher import Dispatcher

    from reduced_models import _exact

    assert isinstance(_exact.run_renewals, Dispatcher)
    idx = _exact.run_renewals._cache._cache_file._load_index()  # the internals cold_kernels relies on
    assert isinstance(idx, dict)
    assert isinstance(cold_kernels(), list)
