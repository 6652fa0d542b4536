"""simulate, evaluate, models and optimizers (filled in next)."""


def simulate(*args, **kwargs):
    raise NotImplementedError


def evaluate(*args, **kwargs):
    raise NotImplementedError


def models(*args, **kwargs):
    raise NotImplementedError


def optimizers(*args, **kwargs):
    raise NotImplementedError
