"""Where a squeeze film ruptures and the solids touch: the gap ``h_c`` the rigid body lands on."""

from __future__ import annotations

__all__ = ["film_rupture_gap"]

#: Film-thickness-to-roughness ratio at the onset of asperity contact (Lambda = h / Rq).
LAMBDA_CONTACT = 3.0


def film_rupture_gap(scene) -> tuple[float, str]:
    """Gap ``h_c`` (m) at which the squeeze film of ``scene`` ruptures and the solids touch.

    With ``[roughness]``: ``3 * rms_height`` (film-thickness-to-roughness ratio
    Lambda = 3, the usual onset of asperity contact).  Without it the surfaces are
    smooth on the model's scale and the film is taken to rupture at the thickness it
    started with, ``[lubricant].film_thickness`` (solid contact from t = 0, the film
    only shares the load while it is squeezed out).

    Parameters
    ----------
    scene : Scene
        A scene with a ``[lubricant]`` section.

    Returns
    -------
    gap : float
        h_c in m.
    source : str
        One line naming the rule.
    """
    if scene.roughness is not None:
        return (
            LAMBDA_CONTACT * scene.roughness.rms_height,
            "3 x [roughness].rms_height (Lambda = 3)",
        )
    return (
        scene.lubricant.film_thickness,
        "[lubricant].film_thickness (no [roughness]: film ruptures where it started)",
    )
