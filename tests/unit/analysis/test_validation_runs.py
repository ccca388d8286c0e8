"""A validation's runs of its conditions are one description's: a reduced model built for them is
trained at that description's own numbers (models/reduced/store.py, ``reduced_training``)."""

import pytest

from feedtherm.analysis import validation


class Stop(Exception):
    pass


def test_a_validations_runs_ask_for_a_reduced_model_trained_at_their_description(paper, monkeypatch):
    asked = []

    def first_run_only(loaded, **arguments):
        asked.append(arguments)
        raise Stop

    monkeypatch.setattr(validation, "simulate", first_run_only)
    with pytest.raises(Stop):
        validation.validate(paper, model="reduced", mesh="coarse")
    (arguments,) = asked
    assert (arguments["model"], arguments["mesh"]) == ("reduced", "coarse")
    assert arguments["options"].reduced_training == "description"
