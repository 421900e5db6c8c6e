namespace LaserEngrave.Simulator.Motion;

/// <summary>The two axes of the X-Y stage, by their place on the chain (X nearest the PC).</summary>
public enum AxisName
{
    X,
    Y,
}
