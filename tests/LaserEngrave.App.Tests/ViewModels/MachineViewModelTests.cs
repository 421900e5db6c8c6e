using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class MachineViewModelTests
{
    private readonly Fakes _fakes = new();

    private MachineViewModel NewMachine() => new(_fakes.Factory, MachineProfile.Default);

    [Fact]
    public async Task Connect_Simulator_ConnectedWithIdentityAndPositions()
    {
        var machine = NewMachine();

        await machine.ConnectCommand.ExecuteAsync(null);

        Assert.True(machine.IsConnected);
        Assert.Null(machine.Error);
        Assert.Contains("PICGATE FAKE", machine.Identity, StringComparison.Ordinal);
        Assert.Equal(0, machine.XMicrosteps);
        Assert.True(machine.XHomed);
        Assert.Equal("off", machine.GateState);
        await _fakes.Factory.Received(1).ConnectAsync(MachineChoice.Simulator, MachineProfile.Default, Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Connect_PortFails_ErrorShownAndNotConnected()
    {
        _fakes.Factory.ConnectAsync(Arg.Any<MachineChoice>(), Arg.Any<MachineProfile>(), Arg.Any<CancellationToken>())
            .Throws(new DeviceException("COM9: the port does not exist"));
        var machine = NewMachine();
        machine.UseSimulator = false;
        machine.StagePort = "COM9";
        machine.LaserPort = "COM10";

        await machine.ConnectCommand.ExecuteAsync(null);

        Assert.False(machine.IsConnected);
        Assert.Equal("COM9: the port does not exist", machine.Error);
        await _fakes.Factory.Received(1).ConnectAsync(new MachineChoice(false, "COM9", "COM10"), Arg.Any<MachineProfile>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Connect_GateSilent_ErrorShownAndConnectionClosed()
    {
        _fakes.Gate.IdentifyAsync(Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceTimeoutException("laser gate: no reply to *IDN? within 500 ms"));
        var machine = NewMachine();

        await machine.ConnectCommand.ExecuteAsync(null);

        Assert.False(machine.IsConnected);
        Assert.Contains("no reply", machine.Error, StringComparison.Ordinal);
        await _fakes.Connection.Received(1).DisposeAsync();
    }

    [Fact]
    public async Task Identify_NotConnected_ErrorSaysConnectFirst()
    {
        var machine = NewMachine();

        await machine.IdentifyCommand.ExecuteAsync(null);

        Assert.Contains("not connected", machine.Error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Home_Connected_LaserOffThenBothAxesHomed()
    {
        var machine = NewMachine();
        await machine.ConnectCommand.ExecuteAsync(null);
        _fakes.Gate.ClearReceivedCalls();

        await machine.HomeCommand.ExecuteAsync(null);

        Assert.Null(machine.Error);
        Received.InOrder(() =>
        {
            _fakes.Gate.OffAsync(Arg.Any<CancellationToken>());
            _fakes.X.HomeAsync(Arg.Any<CancellationToken>());
        });
        await _fakes.Y.Received(1).HomeAsync(Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Home_AxisFails_ErrorShown()
    {
        _fakes.Y.HomeAsync(Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceException("stage: device 2 (Y) replied error 255, busy"));
        var machine = NewMachine();
        await machine.ConnectCommand.ExecuteAsync(null);

        await machine.HomeCommand.ExecuteAsync(null);

        Assert.Contains("busy", machine.Error, StringComparison.Ordinal);
        Assert.False(machine.IsBusy);
    }

    [Fact]
    public async Task Disconnect_Connected_ClosesConnectionAndClearsState()
    {
        var machine = NewMachine();
        await machine.ConnectCommand.ExecuteAsync(null);

        await machine.DisconnectCommand.ExecuteAsync(null);

        Assert.False(machine.IsConnected);
        Assert.Null(machine.XMicrosteps);
        await _fakes.Connection.Received(1).DisposeAsync();
    }

    [Fact]
    public void RefreshPorts_FactoryLists_PortsShown()
    {
        _fakes.Factory.ListPorts().Returns(["COM3", "COM4"]);
        var machine = NewMachine();

        machine.RefreshPorts();

        Assert.Equal(["COM3", "COM4"], machine.Ports);
    }
}
