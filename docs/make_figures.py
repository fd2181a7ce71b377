"""Regenerate the figures in docs/img/ (python docs/make_figures.py)."""

import os

import exactinv as ei
from exactinv import display

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "img")

S = ei.LinearSystem([[-1, 1], [-1, -1]])
BOX = ei.Polyhedron.box([-1, -1], [1, 1])
OCT = ei.Polyhedron.from_vertices([["1", "1/2"], ["1/2", "1"], ["-1/2", "1"], ["-1", "1/2"],
                                   ["-1", "-1/2"], ["-1/2", "-1"], ["1/2", "-1"], ["1", "-1/2"]])
E2_S = ei.LinearSystem([[-1, 2], [0, 1]])
ORTHANT = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
GROWTH = ei.LinearSystem([[1]])  # x' = x leaves [-1, 1]; backward Euler keeps it for dt = 0 and dt >= 2
SEGMENT = ei.Polyhedron.box([-1], [1])


def main():
    os.makedirs(OUT, exist_ok=True)
    figures = {
        "f_i.png": display.plot_f_i(ei.steplength_threshold(S, BOX, ei.methods.taylor(4))),
        "coefficients.png": display.plot_coefficients(ei.methods.ssprk_s1(3), count=4, upto=5.0),
        "valid_set.png": display.plot_valid_set(S, BOX, ei.methods.taylor(4)),
        "valid_set_e2.png": display.plot_valid_set(E2_S, ORTHANT, ei.methods.backward_euler(), upto=2.0),
        "valid_set_split.png": display.plot_valid_set(GROWTH, SEGMENT, ei.methods.backward_euler(), upto=3.0),
        "images.png": display.plot_images(ei.LinearSystem([["-1/2", 1], [-1, "-1/2"]]), OCT, ei.methods.heun(),
                                          ["1/2", "3/2", "2"]),
    }
    for name, fig in figures.items():
        fig.savefig(os.path.join(OUT, name), dpi=110)
        print("wrote", os.path.join("docs", "img", name))


if __name__ == "__main__":
    main()
