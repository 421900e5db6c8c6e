namespace LaserEngrave.Simulator.Marks;

/// <summary>Whether a code burned on the twin reads, and by how much.</summary>
/// <param name="Text">The code's text.</param>
/// <param name="Reads">ZXing read the burned picture back to <paramref name="Text"/>.</param>
/// <param name="Decoded">What ZXing read (another text counts as not reading), or null.</param>
/// <param name="ModuleUm">The module burned.</param>
/// <param name="SpotDiameterUm">The spot it was burned with.</param>
/// <param name="ModulesRight">Modules whose burned area is on the right side of half (dark ones more than half burned, light ones less).</param>
/// <param name="Modules">Modules of the code.</param>
/// <param name="WorstModulePercent">The worst module: how much of it is as it should be (burned for a dark one, unburned for a light one), %.</param>
/// <param name="TwinSeconds">The twin's time for the code alone, s.</param>
/// <param name="EstimatedSeconds">The estimate for the same, s.</param>
public sealed record ReadabilityVerdict(
    string Text,
    bool Reads,
    string? Decoded,
    double ModuleUm,
    double SpotDiameterUm,
    int ModulesRight,
    int Modules,
    double WorstModulePercent,
    double TwinSeconds,
    double EstimatedSeconds);
