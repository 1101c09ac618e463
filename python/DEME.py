"""The paper's name for the module: `import DEME` is `import deme` (the same module object)."""
import sys

import deme

sys.modules[__name__] = deme
