# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a sheet's computation raises when its inputs cannot make a sheet."""


class SheetError(ValueError):
    """A sheet cannot be built from its inputs; the message names the offending input."""


#: The error of a solve stopped by the user (through its progress indicator).
CANCELLED = "the solve was cancelled; recompute to solve again"
