namespace LaserEngrave.Simulator.Motion;

/// <summary>The axes of the stage, by their place on the chain (X nearest the PC, then Y, then the focus axis Z when there is one).</summary>
public enum AxisName
{
    X,
    Y,

    /// <summary>The focus axis, third on the chain when the machine profile has one.</summary>
    Z,
}
