"""The electrical path of a contact (docs/DESIGN.md "Electrical path", docs/physics.md sections 8, 12, 13).

- :mod:`.spots`: the paper's model, Holm spots with Cooper's alleviation in parallel (Eqs. 15-17);
- :mod:`.cluster`: Greenwood's (1966) constriction of the whole cluster of spots, by the
  DC-FFT 1/r operator of the elastic deformation;
- :mod:`.film`: conduction through the lubricant film, ohmic and Simmons tunnelling;
- :mod:`.path`: how the three combine into ``contact_resistance`` (what the solver calls).
"""

from lubecontact.physics.electrical.path import ElectricalPath, electrical_path
from lubecontact.physics.electrical.spots import MAX_AREA_FRACTION, alleviation_factor, contact_resistance

__all__ = ["MAX_AREA_FRACTION", "ElectricalPath", "alleviation_factor", "contact_resistance", "electrical_path"]
