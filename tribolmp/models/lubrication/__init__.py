"""Lubrication: reduced squeeze/sliding forces, the Eq. 13 pair law, a Reynolds reference,
film dynamics, mixed lubrication and lubricated polishing (SI units)."""
