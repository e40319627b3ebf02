"""The compiled module gonio._core (host/python), loaded where it is used: the readers work without it."""
import re


class StackError(ValueError):
    """A stack gonio refuses: `file:line: reason` as the command line says it, and for a stack built from a dict
    the key instead of the line. Attributes: file, line, key (None where the stack came from a file), reason."""

    def __init__(self, message, file=None, line=None, key=None, reason=None):
        super().__init__(message)
        self.file, self.line, self.key, self.reason = file, line, key, reason


def core():
    """gonio._core, or an ImportError saying how to build it."""
    try:
        from . import _core
    except ImportError as e:
        raise ImportError("gonio's in-process API needs its compiled module gonio._core: `pip install ./python` "
                          "(or `./run build`, with build/python on PYTHONPATH); the readers (gonio.read_run, ...) "
                          "work without it") from e
    return _core


def checked(stack, call):
    """call(text, path) on the stack's TOML, its refusal raised as gonio.StackError naming the key where the stack
    was built from a dict."""
    return checked_text(*stack.toml(), call)


def checked_text(text, path, where, call):
    """call(text, path), gonio._core's StackError raised as gonio.StackError (`where`: line -> key, or None)."""
    try:
        return call(text, path)
    except core().StackError as e:
        line = getattr(e, "line", None)
        message = str(e)
        reason = re.sub(r"^.*?:\d+: ", "", message, count=1)
        if where is None:
            raise StackError(message, file=path, line=line, reason=reason) from None
        key = where.get(line)
        if key is None:   # a refusal of the whole stack (its first line): no one key
            key = "stack"
        raise StackError(f"{key}: {reason}", file=path, line=line, key=key, reason=reason) from None
