"""Errors that reach the user as messages, never as tracebacks."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Problem", "InputError", "CatalogError", "Terminated"]


@dataclass(frozen=True)
class Problem:
    """One problem with one input field: what is wrong and what is accepted."""

    field: str
    value: object
    accepted: str

    def __str__(self) -> str:
        if self.value is None:
            return f"{self.field}: missing; expected {self.accepted}"
        return f"{self.field}: got {self.value!r}; accepted: {self.accepted}"


class InputError(ValueError):
    """Bad input: carries one :class:`Problem` per offending field.

    The CLI prints each problem on its own line and exits with code 2.
    """

    def __init__(self, problems: list[Problem] | Problem):
        if isinstance(problems, Problem):
            problems = [problems]
        self.problems = list(problems)
        super().__init__("\n".join(str(p) for p in self.problems))


class CatalogError(InputError):
    """An unknown catalog, part or constant; the message lists valid choices."""


class DeclarationError(Exception):
    """A declaration synth was given that it cannot honour (a registered check whose physics reads a value its
    group does not have, such as another part family's): the configuration's error, the same for every application.
    Not an :class:`InputError`, so no per-application handler takes it for one application's refused input (a bulk
    row, a relaxation probe); every path stops with it, the command line with exit 2. Carries its :class:`Problem`
    as :class:`InputError` does."""

    def __init__(self, problem: Problem):
        self.problems = [problem]
        super().__init__(str(problem))


class Terminated(KeyboardInterrupt):
    """SIGTERM during a command (``synth.cli`` raises it from its signal handler): stop as on Ctrl-C, exit 143."""
