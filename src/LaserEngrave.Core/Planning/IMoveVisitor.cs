namespace LaserEngrave.Core.Planning;

/// <summary>Receives a plan's moves one at a time, in order, without the plan allocating anything per move.</summary>
/// <remarks>Implement it on a struct and pass it by reference to <see cref="RasterPlan.Visit{TVisitor}(ref TVisitor)"/> so the calls inline.</remarks>
public interface IMoveVisitor
{
    void Visit(in Move move);
}
